"""The sharp-interface columns (issue 18, item 5): volume_sharp, surface_sharp and
bending_energy_sharp measure the zero level set of phi itself, the limits the diffuse
columns tend to as eps -> 0 (docs/scenes.md). On a circle of radius 1 (eps 0.05, 4 points
across the interface) they meet pi, 2 pi and pi / Be: measured 6e-6, 3e-6 and 2e-3
relative, asserted to 1e-4, 1e-4 and 1e-2 (the bending uses the curvature from mu and
grad phi, one order less accurate than the measures). The diffuse columns differ from them
by O(eps^2) terms: volume by 4e-3, helfrich_energy / (2 sqrt2 / 3) by 1e-3 here.
`cellphase check` reports each cell's reduced area from its sharp initial shape."""
import math
import re
import subprocess

import yaml

from conftest import EXE, circle_scene, require_exe, run_scene


def test_sharp_columns_of_a_circle_meet_the_exact_values(tmp_path):
    scene = circle_scene("helfrich_hm1", epsilon=0.05, end_time=2e-4, dt=1e-4)
    scene["phase_field"]["penalty_area"] = 100
    scene["numbers"] = {"Be": 2.0}
    obs = run_scene(scene, tmp_path)
    volume, surface, bending = (obs[k][-1] for k in ("volume_sharp", "surface_sharp",
                                                    "bending_energy_sharp"))
    assert abs(volume / math.pi - 1) < 1e-4, volume
    assert abs(surface / (2 * math.pi) - 1) < 1e-4, surface
    assert abs(bending / (math.pi / 2.0) - 1) < 1e-2, bending
    # The diffuse columns tend to them: (2 sqrt2 / 3) E_bending and int phi~.
    assert abs(obs["helfrich_energy"][-1] / (2 * math.sqrt(2) / 3) / bending - 1) < 1e-2
    assert 0 < obs["volume"][-1] / volume - 1 < 1e-2


def test_check_reports_the_reduced_area_of_each_sharp_shape(tmp_path):
    require_exe()
    scene = circle_scene("helfrich_hm1")
    scene["cells"] = [{"name": "oval", "shape": "ellipse", "center": [0, 0], "semi_axes": [1.6, 0.5]},
                      {"name": "round", "shape": "circle", "center": [0, 1.3], "radius": 0.4}]
    scene["domain"]["upper"] = [2, 2.5]
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(scene))
    out = subprocess.run([EXE, "check", str(path)], capture_output=True, text=True).stdout
    match = re.search(r"reduced area\s+([0-9.]+) \(oval\), ([0-9.]+) \(round\)", out)
    assert match, out
    a, b = 1.6, 0.5  # Ramanujan's perimeter of the ellipse, exact to 1e-5 relative here
    perimeter = math.pi * (3 * (a + b) - math.sqrt((3 * a + b) * (a + 3 * b)))
    assert abs(float(match.group(1)) - 4 * math.pi * math.pi * a * b / perimeter**2) < 2e-3
    assert abs(float(match.group(2)) - 1) < 2e-3
