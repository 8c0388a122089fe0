"""python/reaction_models.py: the species and kinetics of a reaction-diffusion form file
become the table the scene reader checks against, so that a new species or constant is an
edit of the form file alone."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "python" / "reaction_models.py"


def generate(tmp_path, text):
    form = tmp_path / "toy.py"
    form.write_text(text)
    return subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), str(form)],
                          capture_output=True, text=True)


def test_the_literals_of_a_form_file_become_the_table(tmp_path):
    proc = generate(tmp_path, 'from ufl import dx\nspecies = {"a": ("membrane", 2.0), '
                              '"B": ("bulk", 5.0), "d": ("membrane", 0.5)}\n'
                              'kinetics = {"k_on": 1.5, "k_off": 0.25}\nprotrusion = "d"\n'
                              'a = 1 * dx  # a UFL expression, not a literal\n')
    assert proc.returncode == 0, proc.stderr
    table = (tmp_path / "reaction_models.cpp").read_text()
    assert '{"a", true, 2.0}' in table and '{"B", false, 5.0}' in table
    assert '{"k_on", 1.5}' in table and '{"k_off", 0.25}' in table
    assert '{"toy", species_toy, 3, kinetics_toy, 2, "d"}' in table


def test_the_gtpase_form_declares_table_5_1(tmp_path):
    proc = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path),
                           str(ROOT / "forms" / "gtpase.py")], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    table = (tmp_path / "reaction_models.cpp").read_text()
    for row in ['{"c1", true, 1.0}', '{"c2", true, 1.0}', '{"C", false, 20.0}',
                '{"a2", 160.0}', '{"a4", 0.333}', '{"gamma", 400.0}']:
        assert row in table


def test_a_bad_declaration_is_refused_naming_it(tmp_path):
    proc = generate(tmp_path, 'species = {"a": ("cytosol", 1.0)}\nkinetics = {}\nprotrusion = "a"\n')
    assert proc.returncode != 0 and "'cytosol'" in proc.stderr
    proc = generate(tmp_path, 'species = {"a": ("bulk", 1.0)}\nkinetics = {}\nprotrusion = "z"\n')
    assert proc.returncode != 0 and "'z'" in proc.stderr
    proc = generate(tmp_path, 'species = {"a": ("bulk", 1.0)}\nprotrusion = "a"\n')
    assert proc.returncode != 0 and "kinetics" in proc.stderr
