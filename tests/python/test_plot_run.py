"""python/plot_run.py and python/cellphase_results.py on small synthetic run directories.

The synthetic fields.xdmf copies the layout DOLFINx 0.5.2 writes: mesh grids `meshK`
under /Xdmf/Domain (one written after the field collections, as DOLFINx does after a
remesh) and Temporal collections whose grids point at their mesh with an xpointer.
"""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")  # Debian package python3-h5py

PYTHON_DIR = Path(__file__).resolve().parents[2] / "python"
SCRIPT = PYTHON_DIR / "plot_run.py"
sys.path.insert(0, str(PYTHON_DIR))
from cellphase_results import read_fields, read_observables, zero_level_set_2d  # noqa: E402

COLUMNS = ("time,step,volume,surface,helfrich_energy,total_energy,energy_ch,center_x,center_y,"
           "center_z,circularity,phi_min,phi_max,lambda_volume,lambda_area,dofs,"
           "remesh_volume_change,wall_assembly,wall_factorise,wall_solve,wall_remesh,wall_output")


def square_mesh(n, half_width=1.0):
    """Structured triangle mesh of [-w, w]^2 with n x n squares cut in two."""
    x = np.linspace(-half_width, half_width, n + 1)
    points = np.array([(xi, yj) for yj in x for xi in x])
    cells = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i, (j + 1) * (n + 1) + i + 1
            cells += [(a, b, d), (a, d, c)]
    return points, np.array(cells, dtype=np.int64)


def circle_phi(points, radius, eps=0.05):
    r = np.linalg.norm(points, axis=1)
    return np.tanh((radius - r) / (np.sqrt(2) * eps))


def mesh_grid(name, points, cells):
    return f"""    <Grid Name="{name}" GridType="Uniform">
      <Topology TopologyType="Triangle" NumberOfElements="{len(cells)}" NodesPerElement="3">
        <DataItem Dimensions="{len(cells)} 3" NumberType="Int" Format="HDF">fields.h5:/Mesh/{name}/topology</DataItem>
      </Topology>
      <Geometry GeometryType="XY">
        <DataItem Dimensions="{len(points)} 2" Format="HDF">fields.h5:/Mesh/{name}/geometry</DataItem>
      </Geometry>
    </Grid>
"""


def field_grid(field, mesh, time, key, n_points):
    return f"""      <Grid Name="{field}" GridType="Uniform">
        <xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='{mesh}']/*[self::Topology or self::Geometry])" />
        <Time Value="{time}" />
        <Attribute Name="{field}" AttributeType="Scalar" Center="Node">
          <DataItem Dimensions="{n_points} 1" Format="HDF">fields.h5:/Function/{field}/{key}</DataItem>
        </Attribute>
      </Grid>
"""


def write_run(run_dir, with_fields=True):
    """observables.csv with 4 steps; fields phi and mu at times 0, 0.5 (mesh0) and 1 (mesh1)."""
    run_dir.mkdir()
    rows = [f"{0.25 * k},{k},{3.1 - 0.1 * k},{6.2 - 0.1 * k},0,{5.9 - 0.2 * k},{5.9 - 0.2 * k},"
            f"0,0,0,1.001,-1,1,0,0,{441 + 50 * (k // 2)},0,0.01,0.1,0.005,{0.2 * (k == 2)},0.001"
            for k in range(4)]
    (run_dir / "observables.csv").write_text(COLUMNS + "\n" + "\n".join(rows) + "\n")
    if not with_fields:
        return
    meshes = {"mesh0": square_mesh(20), "mesh1": square_mesh(24)}
    outputs = [(0.0, "0", "mesh0", 0.8), (0.5, "0_5", "mesh0", 0.7), (1.0, "1", "mesh1", 0.6)]
    with h5py.File(run_dir / "fields.h5", "w") as f:
        for name, (points, cells) in meshes.items():
            f[f"Mesh/{name}/geometry"] = points
            f[f"Mesh/{name}/topology"] = cells
        for _, key, mesh, radius in outputs:
            phi = circle_phi(meshes[mesh][0], radius)
            f[f"Function/phi/{key}"] = phi[:, None]
            f[f"Function/mu/{key}"] = (0.1 * phi)[:, None]
    collections = ""
    for field in ("phi", "mu"):
        collections += f'    <Grid Name="{field}" GridType="Collection" CollectionType="Temporal">\n'
        for time, key, mesh, _ in outputs:
            collections += field_grid(field, mesh, time, key, len(meshes[mesh][0]))
        collections += "    </Grid>\n"
    (run_dir / "fields.xdmf").write_text(
        '<?xml version="1.0"?>\n<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n'
        '<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">\n  <Domain>\n'
        + mesh_grid("mesh0", *meshes["mesh0"]) + collections + mesh_grid("mesh1", *meshes["mesh1"])
        + "  </Domain>\n</Xdmf>\n")


def plot_run(*args):
    return subprocess.run(["/usr/bin/python3", str(SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def test_reads_synthetic_run(tmp_path):
    run = tmp_path / "run"
    write_run(run)
    obs = read_observables(run)
    assert list(obs["step"]) == [0, 1, 2, 3]
    outputs = list(read_fields(run))
    assert [t for t, *_ in outputs] == [0.0, 0.5, 1.0]
    # The xpointers must resolve to the right mesh, including mesh1 written after the fields.
    assert [len(points) for _, points, _, _ in outputs] == [21 * 21, 21 * 21, 25 * 25]
    time, points, cells, values = outputs[2]
    assert cells.shape == (2 * 24 * 24, 3) and set(values) == {"phi", "mu"}
    assert values["phi"].shape == (len(points),)


def test_writes_plots(tmp_path):
    run = tmp_path / "run"
    write_run(run)
    result = plot_run(run, "--fields", "phi", "mu")
    assert result.returncode == 0, result.stderr
    for name in ("observables.png", "timings.png", "level_sets.png", "level_sets_mu.png"):
        png = run / "plots" / name
        assert png.is_file() and png.stat().st_size > 0, name
        assert str(png) in result.stdout


def test_without_fields_plots_observables_only(tmp_path):
    run = tmp_path / "run"
    write_run(run, with_fields=False)
    result = plot_run(run, "--out", tmp_path / "out")
    assert result.returncode == 0, result.stderr
    assert "fields.xdmf not found" in result.stdout
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["observables.png", "timings.png"]


def test_level_set_of_circle():
    points, cells = square_mesh(200)
    curves = zero_level_set_2d(points, cells, circle_phi(points, 0.5))
    assert len(curves) == 1
    radius = np.linalg.norm(curves[0], axis=1)
    assert abs(radius.mean() - 0.5) < 1e-2
    assert radius.std() < 1e-2


@pytest.mark.parametrize("make", [False, True], ids=["missing-dir", "no-observables"])
def test_clear_error(tmp_path, make):
    run = tmp_path / "run"
    if make:
        run.mkdir()
    result = plot_run(run)
    assert result.returncode != 0
    assert "Traceback" not in result.stderr
    expected = "observables.csv: no such file" if make else "no such directory"
    assert f"plot_run.py: error: {run}" in result.stderr and expected in result.stderr, result.stderr
