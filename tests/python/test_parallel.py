"""The same scene on 2 MPI ranks gives the observables of the serial run. Remeshing and
field transfer stay rank-local (refinement without redistribution), so the meshes are the
same; what differs is the order of floating-point sums and MUMPS' pivoting, which after
30 steps changes the observables by less than 1e-8 relative."""
from conftest import circle_scene, run_scene


def test_two_ranks_match_serial(tmp_path):
    scene = circle_scene("helfrich_lagrange", epsilon=0.08, end_time=0.03, dt=1e-3)
    scene["cells"] = [{"shape": "ellipse", "center": [0.1, 0], "semi_axes": [1.2, 0.7]}]
    scene["numerics"]["mesh"]["remesh_every"] = 10
    (tmp_path / "serial").mkdir()
    (tmp_path / "mpi").mkdir()
    serial = run_scene(scene, tmp_path / "serial")
    parallel = run_scene(scene, tmp_path / "mpi", ranks=2)
    assert serial["dofs"] == parallel["dofs"]
    for key in ("volume", "surface", "helfrich_energy", "center_x", "circularity"):
        for a, b in zip(serial[key], parallel[key]):
            assert abs(a - b) <= 1e-8 * max(abs(a), 1.0), f"{key}: {a} vs {b}"
