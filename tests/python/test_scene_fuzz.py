"""Scene fuzzing: 500 mutations of the demo scenes (wrong types, missing and unknown keys,
huge, negative, NaN and zero values, empty files, binary bytes, deep nesting, very long
values) given to `cellphase check`. None may crash, hang or print a stack trace: each ends
with exit 0 (the mutation happened to be valid) or exit 2 with an `error:` message."""
import concurrent.futures
import copy
import random
import subprocess
from pathlib import Path

import pytest
import yaml

from conftest import EXE, require_exe

ROOT = Path(__file__).resolve().parents[2]
DEMOS = sorted(ROOT.glob("demos/*/scene.yaml"))
BAD_VALUES = [None, "", "text", -1, 0, 1e308, -1e308, float("nan"), float("inf"), True,
              [], {}, [1, 2, 3, 4, 5], {"x": 1}, "x" * 10000, 10**30]
CRASH_SIGNS = ("Traceback", "terminate called", "Segmentation", "Aborted", "core dumped",
               "stack trace")


def paths(node, prefix=()):
    """Every key path of a nested YAML structure."""
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else []
    for k, v in items:
        yield prefix + (k,)
        yield from paths(v, prefix + (k,))


def set_path(doc, path, value):
    node = doc
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value


def delete_path(doc, path):
    node = doc
    for k in path[:-1]:
        node = node[k]
    del node[path[-1]]


def mutate(rng, base):
    """One mutated scene as bytes."""
    kind = rng.randrange(10)
    if kind == 0:
        return b""
    if kind == 1:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400)))
    doc = copy.deepcopy(base)
    keys = list(paths(doc))
    path = rng.choice(keys)
    if kind in (2, 3, 4):
        set_path(doc, path, rng.choice(BAD_VALUES))
    elif kind == 5:
        delete_path(doc, path)
    elif kind == 6:
        parent = doc
        for k in path[:-1]:
            parent = parent[k]
        if isinstance(parent, dict):
            parent["unknown_" + str(rng.randrange(100))] = 1
        else:
            set_path(doc, path, "unknown")
    elif kind == 7:
        nested = 1
        for _ in range(rng.randrange(20, 200)):
            nested = {"a": nested}
        set_path(doc, path, nested)
    elif kind == 8:
        value = doc
        for k in path:
            value = value[k]
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            set_path(doc, path, value * rng.choice([-1, 0, 1e-12, 1e12, 3]))
        else:
            set_path(doc, path, rng.choice(BAD_VALUES))
    else:
        text = yaml.safe_dump(doc).encode()
        cut = rng.randrange(len(text))
        return text[:cut] + rng.choice([b":", b"[", b"{", b"\t", b"- ", b"\x00"]) + text[cut:]
    return yaml.safe_dump(doc, allow_unicode=True).encode()


def check(path):
    try:
        proc = subprocess.run([EXE, "check", str(path)], capture_output=True, timeout=60)
    except subprocess.TimeoutExpired:
        return path, None, b"", b"timeout"
    return path, proc.returncode, proc.stdout, proc.stderr


def test_mutated_scenes_never_crash(tmp_path):
    require_exe()
    rng = random.Random(20261123)
    bases = [yaml.safe_load(p.read_text()) for p in DEMOS]
    files = []
    for i in range(500):
        f = tmp_path / f"scene{i:03d}.yaml"
        f.write_bytes(mutate(rng, rng.choice(bases)))
        files.append(f)
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(check, files))
    errors = valid = 0
    for path, code, out, err in results:
        text = err.decode(errors="replace")
        assert code is not None, f"{path.name}: hangs"
        assert not any(s in text for s in CRASH_SIGNS), f"{path.name}: {text[:500]}"
        assert code in (0, 2), f"{path.name}: exit {code}: {text[:500]}"
        if code == 2:
            assert text.startswith("error: ") and len(text.strip()) > 10, f"{path.name}: {text[:200]}"
            errors += 1
        else:
            valid += 1
    print(f"{errors} rejected with a message, {valid} valid")
    assert errors > 400  # nearly every mutation is invalid: the test really exercises errors
