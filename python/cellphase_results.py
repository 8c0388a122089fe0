"""Read the output of a cellphase run: observables.csv and fields.xdmf/fields.h5.

    obs = read_observables(run_dir)          # {"time": array, "volume": array, ...}
    for time, points, cells, values in read_fields(run_dir):
        curves = zero_level_set_2d(points, cells, values["phi"])

fields.xdmf is the XDMF 3 file written by DOLFINx: each mesh is a Uniform grid
`meshK` under /Xdmf/Domain, each field a Temporal collection whose children point
at their mesh through an xi:include xpointer. The mesh changes with remeshing, so
points and cells are returned per output time. Needs h5py (Debian: python3-h5py).
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


def _mesh_elements(grid, domain):
    """Topology and Geometry of a field's grid, following its xpointer to a mesh grid."""
    include = grid.find(XINCLUDE)
    if include is None:  # mesh written inline in the grid itself
        return grid.find("Topology"), grid.find("Geometry")
    # DOLFINx writes xpointer(/Xdmf/Domain/Grid[@Name='meshK']/*[self::Topology or ...]).
    match = re.search(r"Grid\[@Name='([^']+)'\]", include.get("xpointer", ""))
    if not match:
        raise ResultsError(f"unsupported xpointer {include.get('xpointer')!r}")
    mesh = domain.find(f"Grid[@Name='{match.group(1)}']")
    if mesh is None:
        raise ResultsError(f"fields.xdmf refers to mesh {match.group(1)!r}, which it does not hold")
    return mesh.find("Topology"), mesh.find("Geometry")


def _parse_xdmf(run_dir):
    path = Path(run_dir) / "fields.xdmf"
    if not path.is_file():
        raise ResultsError(f"{path}: no such file (the run wrote no fields)")
    try:
        domain = ET.parse(path).getroot().find("Domain")
    except ET.ParseError as e:
        raise ResultsError(f"{path}: not valid XML (is the run still writing it?): {e}") from None
    if domain is None:
        raise ResultsError(f"{path}: no /Xdmf/Domain element")
    return domain


def describe_fields(run_dir):
    """(field names, dimension) of RUN_DIR/fields.xdmf; dimension 2 for triangle meshes,
    3 for tetrahedra, None if unknown."""
    domain = _parse_xdmf(run_dir)
    names = [g.get("Name") for g in domain.findall("Grid") if g.get("CollectionType") == "Temporal"]
    topology = domain.find(".//Topology")
    dims = {"Triangle": 2, "Tetrahedron": 3}
    return names, None if topology is None else dims.get(topology.get("TopologyType"))


def read_fields(run_dir, fields=None):
    """Yield (time, points, cells, {field: nodal values}) for each output time, in time order.

    points is N x gdim (2 for XY, 3 for XYZ), cells M x 3 (triangles) or M x 4
    (tetrahedra). `fields` restricts which fields are read (default: all).
    """
    domain = _parse_xdmf(run_dir)
    # Group the children of all temporal collections by (time, mesh): fields written
    # at the same step share the mesh of that step.
    steps = {}
    for collection in domain.findall("Grid"):
        name = collection.get("Name")
        if collection.get("CollectionType") != "Temporal" or (fields and name not in fields):
            continue
        for grid in collection.findall("Grid"):
            time = float(grid.find("Time").get("Value"))
            topology, geometry = _mesh_elements(grid, domain)
            entry = steps.setdefault((time, topology), (geometry, {}))
            entry[1][name] = grid.find("Attribute/DataItem")

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
