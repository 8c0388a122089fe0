"""Read the output of a cellphase run: observables.csv and the fields (fields.xdmf or
fields.pvd, whichever output.format wrote).

    obs = read_observables(run_dir)          # {"time": array, "volume": array, ...}
    for time, points, cells, values in read_fields(run_dir):
        curves = zero_level_set_2d(points, cells, values["phi"])

fields.xdmf (XDMF 3) is a temporal collection with one Uniform grid per output time: its
Topology and Geometry (fields/mesh-<m>.h5) and every field as an Attribute
(fields/step-<n>.h5). Needs h5py (Debian: python3-h5py). Indexes of older cellphase
versions, one temporal collection per field pointing at mesh grids through xpointers, are
read as well.
fields.pvd (VTK) lists one .pvtu/.vtu per time, written with second-order Lagrange cells;
read_fields returns them split into linear cells on the P2 nodes (4 triangles or 8
tetrahedra per cell), ghost cells of the parallel pieces left out.
The mesh changes with remeshing, so points and cells are returned per output time.
"""
import csv
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

XINCLUDE = "{http://www.w3.org/2001/XInclude}include"


class ResultsError(Exception):
    """A run directory is missing a file or holds one that cannot be read."""


def read_observables(run_dir):
    """Columns of RUN_DIR/observables.csv as {name: float array}, one entry per step."""
    path = Path(run_dir) / "observables.csv"
    if not path.is_file():
        raise ResultsError(f"{path}: no such file (is {run_dir} a cellphase run directory?)")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ResultsError(f"{path}: empty file")
    header = rows[0]
    # A running simulation may have written only part of its last line: keep whole rows.
    body = [r for r in rows[1:] if len(r) == len(header)]
    try:
        data = np.array(body, dtype=float).reshape(len(body), len(header))
    except ValueError as e:
        raise ResultsError(f"{path}: {e}") from None
    return {name: data[:, i] for i, name in enumerate(header)}


def _data_item(item, run_dir, h5files):
    """Array of a DataItem: `file.h5:/path` (Format="HDF") or inline text (Format="XML")."""
    dims = [int(d) for d in item.get("Dimensions").split()]
    text = item.text.strip()
    if item.get("Format", "XML") == "XML":
        return np.array(text.split(), dtype=float).reshape(dims)
    # The dataset path never contains ':', so the last one separates it from the file.
    filename, dataset = text.rsplit(":", 1)
    if filename not in h5files:
        import h5py  # imported here so that reading observables alone does not need it
        try:
            h5files[filename] = h5py.File(Path(run_dir) / filename, "r")
        except OSError as e:
            raise ResultsError(f"{Path(run_dir) / filename}: cannot be read "
                               f"(is the run still writing it?): {e}") from None
    try:
        return h5files[filename][dataset][()].reshape(dims)
    except KeyError:
        raise ResultsError(f"{filename}: no dataset {dataset}") from None


def fields_index(run_dir, stem="fields"):
    """RUN_DIR/<stem>.xdmf or RUN_DIR/<stem>.pvd, whichever exists; None if neither.
    stem is "fields" (every field on the shared mesh) or "cell.<name>" (a cell's own mesh,
    with numerics.mesh.cell_meshes: own)."""
    for name in (f"{stem}.xdmf", f"{stem}.pvd"):
        if (Path(run_dir) / name).is_file():
            return Path(run_dir) / name
    return None


def _mesh_elements(grid, domain):
    """Topology and Geometry of a grid: its own, or (older indexes) those of the mesh grid
    its xpointer names."""
    include = grid.find(XINCLUDE)
    if include is None:  # mesh written inline in the grid itself
        return grid.find("Topology"), grid.find("Geometry")
    # xpointer(/Xdmf/Domain/Grid[@Name='meshK']/*[self::Topology or ...]).
    match = re.search(r"Grid\[@Name='([^']+)'\]", include.get("xpointer", ""))
    if not match:
        raise ResultsError(f"unsupported xpointer {include.get('xpointer')!r}")
    mesh = domain.find(f"Grid[@Name='{match.group(1)}']")
    if mesh is None:
        raise ResultsError(f"fields.xdmf refers to mesh {match.group(1)!r}, which it does not hold")
    return mesh.find("Topology"), mesh.find("Geometry")


def _parse_xml(path, what):
    if not path.is_file():
        raise ResultsError(f"{path}: no such file ({what})")
    try:
        return ET.parse(path).getroot()
    except ET.ParseError as e:
        raise ResultsError(f"{path}: not valid XML (is the run still writing it?): {e}") from None


def _parse_xdmf(run_dir, stem="fields"):
    path = Path(run_dir) / f"{stem}.xdmf"
    domain = _parse_xml(path, "the run wrote no fields").find("Domain")
    if domain is None:
        raise ResultsError(f"{path}: no /Xdmf/Domain element")
    return domain


def _xdmf_grids(domain):
    """The grids of every temporal collection, each with its time."""
    for collection in domain.findall("Grid"):
        if collection.get("CollectionType") == "Temporal":
            for grid in collection.findall("Grid"):
                yield float(grid.find("Time").get("Value")), grid


def describe_fields(run_dir, stem="fields"):
    """(field names, dimension) of the run's fields (XDMF or VTK); dimension 2 for
    triangle meshes, 3 for tetrahedra, None if unknown."""
    index = fields_index(run_dir, stem)
    if index is not None and index.suffix == ".pvd":
        datasets = _pvd_datasets(run_dir, stem)
        if not datasets:
            return [], None
        piece = _vtu_pieces(datasets[0][1])[0]
        root = _parse_xml(piece, "a piece of the VTK output")
        names = [a.get("Name") for a in root.find(".//PointData").findall("DataArray")
                 if not a.get("Name").startswith("vtk")]
        types = np.fromstring(root.find(".//Cells/DataArray[@Name='types']").text, sep=" ")
        dim = None if len(types) == 0 else (3 if types[0] in (10, 24, 71) else 2)
        return names, dim
    domain = _parse_xdmf(run_dir, stem)
    names = []
    for _, grid in _xdmf_grids(domain):
        for attribute in grid.findall("Attribute"):
            if attribute.get("Name") not in names:
                names.append(attribute.get("Name"))
    topology = domain.find(".//Topology")
    dims = {"Triangle": 2, "Tetrahedron": 3}
    return names, None if topology is None else dims.get(topology.get("TopologyType"))


def read_fields(run_dir, fields=None, stem="fields"):
    """Yield (time, points, cells, {field: nodal values}) for each output time, in time order.

    points is N x gdim (2 for XY, 3 for XYZ), cells M x 3 (triangles) or M x 4
    (tetrahedra). `fields` restricts which fields are read (default: all); `stem` picks the
    index (default fields; cell.<name> for a cell's own mesh).
    """
    index = fields_index(run_dir, stem)
    if index is not None and index.suffix == ".pvd":
        yield from _read_vtk(run_dir, fields, stem)
        return
    domain = _parse_xdmf(run_dir, stem)
    # Group the attributes by (time, mesh): one grid per time, or (older indexes) one grid
    # per field and time sharing the mesh of that step.
    steps = {}
    for time, grid in _xdmf_grids(domain):
        topology, geometry = _mesh_elements(grid, domain)
        for attribute in grid.findall("Attribute"):
            name = attribute.get("Name")
            if fields and name not in fields:
                continue
            entry = steps.setdefault((time, topology), (geometry, {}))
            entry[1][name] = attribute.find("DataItem")

    h5files = {}
    try:
        for (time, topology), (geometry, items) in sorted(steps.items(), key=lambda kv: kv[0][0]):
            points = _data_item(geometry.find("DataItem"), run_dir, h5files).astype(float)
            cells = _data_item(topology.find("DataItem"), run_dir, h5files).astype(np.int64)
            values = {}
            for name, item in items.items():
                # Scalars are stored N x 1: return them as flat arrays, vectors as N x k.
                array = _data_item(item, run_dir, h5files).reshape(len(points), -1)
                values[name] = array[:, 0] if array.shape[1] == 1 else array
            yield time, points, cells, values
    finally:
        for f in h5files.values():
            f.close()


# VTK cell types of DOLFINx's writer and the linear cells on their nodes (VTK node order:
# vertices, then the edges (0,1), (1,2), (2,0) / (0,1), (1,2), (0,2), (0,3), (1,3), (2,3)).
_SPLIT = {
    5: [[0, 1, 2]], 10: [[0, 1, 2, 3]],
    22: [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]],                # quadratic triangle
    69: [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]],                # Lagrange triangle, order 2
    24: [[0, 4, 6, 7], [4, 1, 5, 8], [6, 5, 2, 9], [7, 8, 9, 3],     # quadratic tetrahedron
         [6, 8, 4, 5], [6, 8, 5, 9], [6, 8, 9, 7], [6, 8, 7, 4]],
}
_SPLIT[71] = _SPLIT[24]                                               # Lagrange tetrahedron, order 2
_NODES = {5: 3, 10: 4, 22: 6, 69: 6, 24: 10, 71: 10}


def _pvd_datasets(run_dir, stem="fields"):
    """[(time, path of its .vtu or .pvtu)] of RUN_DIR/<stem>.pvd."""
    root = _parse_xml(Path(run_dir) / f"{stem}.pvd", "the run wrote no VTK fields")
    return [(float(d.get("timestep")), Path(run_dir) / d.get("file"))
            for d in root.iter("DataSet")]


def _vtu_pieces(path):
    if path.suffix == ".vtu":
        return [path]
    root = _parse_xml(path, "a time of the VTK output")
    return [path.parent / p.get("Source") for p in root.iter("Piece")]


def _ascii_array(node, dtype=float):
    if node.get("format", "ascii") != "ascii":
        raise ResultsError(f"VTK DataArray {node.get('Name')!r}: format {node.get('format')!r} "
                           "is not read (DOLFINx writes ascii)")
    return np.array((node.text or "").split(), dtype=dtype)


def _read_vtu(path, fields):
    """points (N x 3), linear cells (M x k) and point data of one .vtu piece."""
    root = _parse_xml(path, "a piece of the VTK output")
    piece = root.find("UnstructuredGrid/Piece")
    points = _ascii_array(piece.find("Points/DataArray")).reshape(-1, 3)
    cells = piece.find("Cells")
    connectivity = _ascii_array(cells.find("DataArray[@Name='connectivity']"), np.int64)
    offsets = _ascii_array(cells.find("DataArray[@Name='offsets']"), np.int64)
    types = _ascii_array(cells.find("DataArray[@Name='types']"), np.int64)
    ghost = piece.find("CellData/DataArray[@Name='vtkGhostType']")
    owned = np.ones(len(types), bool) if ghost is None else (_ascii_array(ghost, np.int64) & 1) == 0
    if len(set(types)) > 1 or (len(types) and types[0] not in _SPLIT):
        raise ResultsError(f"{path}: cell types {sorted(set(types))} are not read")
    linear = np.empty((0, 3), np.int64)
    if len(types):
        nodes = connectivity.reshape(-1, _NODES[types[0]])
        assert np.array_equal(offsets, np.arange(1, len(types) + 1) * nodes.shape[1])
        nodes = nodes[owned]
        linear = np.concatenate([nodes[:, s] for s in _SPLIT[types[0]]])
    values = {}
    for array in piece.find("PointData").findall("DataArray"):
        name = array.get("Name")
        if name.startswith("vtk") or (fields and name not in fields):
            continue
        data = _ascii_array(array).reshape(len(points), -1)
        values[name] = data[:, 0] if data.shape[1] == 1 else data
    return points, linear, values


def _read_vtk(run_dir, fields, stem="fields"):
    for time, path in sorted(_pvd_datasets(run_dir, stem), key=lambda d: d[0]):
        points, cells, values = [], [], {}
        offset = 0
        for piece in _vtu_pieces(path):
            p, c, v = _read_vtu(piece, fields)
            points.append(p)
            cells.append(c + offset)
            offset += len(p)
            for name, data in v.items():
                values.setdefault(name, []).append(data)
        points = np.concatenate(points)
        cells = np.concatenate(cells)
        if cells.shape[1] == 3 and not np.any(points[:, 2]):
            points = points[:, :2]  # a 2D mesh, as the XDMF reader returns it
        yield time, points, cells, {k: np.concatenate(v) for k, v in values.items()}


def zero_level_set_2d(points, cells, values, level=0.0):
    """Curves where the P1 field `values` on a triangle mesh equals `level` (default 0).

    Returns a list of K x 2 arrays, one per connected piece of the contour.
    """
    import matplotlib.tri as mtri
    from matplotlib.figure import Figure  # a throwaway figure: no pyplot state involved

    triangulation = mtri.Triangulation(points[:, 0], points[:, 1], cells)
    values = np.asarray(values, dtype=float)
    if not (values.min() < level < values.max()):
        return []  # tricontour warns and draws nothing when the level is out of range
    contours = Figure().add_subplot().tricontour(triangulation, values, levels=[level])
    return [seg for seg in contours.allsegs[0] if len(seg) > 1]
