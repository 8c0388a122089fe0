"""Read and check a study file (see docs/studies.md) and list its members.

    study = load_study("vesicle-convergence.yaml")
    for member in study.members:        # Member(name, overrides, eps or None, params)
        ...

A study is either a ladder (a convergence study: epsilon, base resolution and time step
scaled together) or a sweep (the product of lists of values for one or more scene keys).
Every problem raises StudyError with a message that names the study file and the bad key.
"""
import itertools
import re
from dataclasses import dataclass, field
from pathlib import Path

import yaml

TOP_KEYS = {"scene", "output", "set", "ladder", "sweep", "observables", "report"}
LADDER_KEYS = {"epsilon", "rules"}
RESOLUTION_RULES = {"resolution_times_epsilon", "base_cell_over_epsilon"}  # exactly one
RULE_KEYS = RESOLUTION_RULES | {"dt_over_epsilon"}
REPORT_KEYS = {"end_state"}
DEFAULT_OBSERVABLES = ["helfrich_energy", "circularity", "volume", "surface"]


class StudyError(Exception):
    """The study file is missing, unreadable or holds a bad key or value."""


@dataclass
class Member:
    name: str          # directory name under the study's output directory
    overrides: dict    # scene key -> value, passed as --set key=value
    eps: float = None  # ladder members only
    params: dict = field(default_factory=dict)  # sweep members: the varied keys


@dataclass
class Study:
    path: Path
    scene: Path
    output: Path
    kind: str                 # "ladder" or "sweep"
    members: list
    observables: list         # ladder: series compared against the finest member
    end_state: list           # sweep: quantities reported at the last step
    sweep_keys: list = field(default_factory=list)
    common: dict = field(default_factory=dict)  # the study's `set`
    rules: dict = field(default_factory=dict)   # the ladder's rules


def format_value(value):
    """A scene value as written after --set key= (lists as [a,b])."""
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(format_value(v) for v in value) + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _positive_numbers(where, values):
    if not isinstance(values, list) or not values:
        raise StudyError(f"{where}: expected a non-empty list of numbers, got {values!r}")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not v > 0:
            raise StudyError(f"{where}: {v!r} is not a positive number")
    return [float(v) for v in values]


def _check_keys(where, section, allowed):
    if not isinstance(section, dict):
        raise StudyError(f"{where}: expected a mapping, got {section!r}")
    unknown = sorted(set(section) - allowed)
    if unknown:
        prefix = f"{where}." if where else ""
        raise StudyError(f"unknown key {prefix}{unknown[0]}; allowed: {', '.join(sorted(allowed))}")


def _scene_domain(scene_path, common):
    """The base scene's domain.lower, domain.upper and domain.resolution, after the study's
    `set` (for the ladder's resolution)."""
    try:
        domain = dict(yaml.safe_load(scene_path.read_text())["domain"])
        for key in ("lower", "upper", "resolution"):
            domain[key] = common.get(f"domain.{key}", domain.get(key))
        return ([float(x) for x in domain["lower"]], [float(x) for x in domain["upper"]],
                list(domain["resolution"]))
    except (OSError, yaml.YAMLError, KeyError, TypeError, ValueError) as e:
        raise StudyError(f"scene {scene_path}: cannot read domain.lower, upper and resolution "
                         f"({e})") from None


def _ladder_resolution(rules, eps, domain):
    """Base resolution of the member with epsilon eps: n = round(c / eps) on every axis
    (resolution_times_epsilon, square domains), or the base cell size h = c eps on every axis
    (base_cell_over_epsilon: n_i = round(extent_i / h), for domains of any aspect)."""
    lower, upper, resolution = domain
    if "resolution_times_epsilon" in rules:
        return [max(1, round(rules["resolution_times_epsilon"] / eps))] * len(resolution)
    h = rules["base_cell_over_epsilon"] * eps
    return [max(1, round((hi - lo) / h)) for lo, hi in zip(lower, upper)]


def _ladder_members(ladder, scene_path, common, where):
    _check_keys(f"{where}ladder", ladder, LADDER_KEYS)
    for key in sorted(LADDER_KEYS - set(ladder)):
        raise StudyError(f"{where}ladder.{key}: required")
    eps_list = _positive_numbers(f"{where}ladder.epsilon", ladder["epsilon"])
    if len(eps_list) < 2:
        raise StudyError(f"{where}ladder.epsilon: a ladder needs at least two values")
    if any(a <= b for a, b in zip(eps_list, eps_list[1:])):
        raise StudyError(f"{where}ladder.epsilon: values must decrease (finest last, the reference)")
    rules = ladder["rules"]
    _check_keys(f"{where}ladder.rules", rules, RULE_KEYS)
    if "dt_over_epsilon" not in rules:
        raise StudyError(f"{where}ladder.rules.dt_over_epsilon: required")
    if len(RESOLUTION_RULES & set(rules)) != 1:
        raise StudyError(f"{where}ladder.rules: exactly one of "
                         f"{' or '.join(sorted(RESOLUTION_RULES))} is required")
    for key in rules:
        _positive_numbers(f"{where}ladder.rules.{key}", [rules[key]])
    domain = _scene_domain(scene_path, common)
    members = []
    for eps in eps_list:
        # Same points across the interface and the same dt/h on every member (thesis 5.3).
        overrides = {"numerics.epsilon": eps, "numerics.dt": rules["dt_over_epsilon"] * eps,
                     "domain.resolution": _ladder_resolution(rules, eps, domain)}
        members.append(Member(f"eps{eps:g}", overrides, eps=eps))
    return members


def _member_name(params):
    text = "_".join(f"{k.split('.')[-1]}={format_value(v)}" for k, v in params.items())
    return re.sub(r"[^A-Za-z0-9_.=+-]", "", text)


def _sweep_members(sweep, where):
    """The product of the lists. A key naming several scene keys separated by commas varies
    them together: its values are lists with one value per named key."""
    if not isinstance(sweep, dict) or not sweep:
        raise StudyError(f"{where}sweep: expected a mapping of scene keys to lists of values")
    groups = []  # (scene keys, list of value tuples)
    for key, values in sweep.items():
        if not isinstance(values, list) or not values:
            raise StudyError(f"{where}sweep.{key}: expected a non-empty list of values")
        keys = [k.strip() for k in key.split(",")]
        if len(keys) == 1:
            groups.append((keys, [(v,) for v in values]))
            continue
        if not all(keys):
            raise StudyError(f"{where}sweep.{key}: an empty scene key between the commas")
        for v in values:
            if not isinstance(v, list) or len(v) != len(keys):
                raise StudyError(f"{where}sweep.{key}: every value must be a list of {len(keys)} "
                                 f"values, one per key (found {v!r})")
        groups.append((keys, [tuple(v) for v in values]))
    all_keys = [k for keys, _ in groups for k in keys]
    if len(set(all_keys)) != len(all_keys):
        raise StudyError(f"{where}sweep: a scene key is varied twice ({', '.join(all_keys)})")
    members = []
    for combo in itertools.product(*(values for _, values in groups)):
        params = {k: v for (keys, _), values in zip(groups, combo) for k, v in zip(keys, values)}
        members.append(Member(_member_name(params), dict(params), params=params))
    return members, all_keys


def load_study(path):
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except OSError as e:
        raise StudyError(f"{path}: cannot read ({e.strerror})") from None
    except yaml.YAMLError as e:
        raise StudyError(f"{path}: not valid YAML: {e}") from None
    where = f"{path}: "
    if not isinstance(data, dict):
        raise StudyError(f"{where}expected a mapping of keys (scene, output, ladder or sweep, ...)")
    try:
        _check_keys("", data, TOP_KEYS)
    except StudyError as e:
        raise StudyError(f"{where}{e}") from None
    for key in ("scene", "output"):
        if not isinstance(data.get(key), str):
            raise StudyError(f"{where}{key}: required (a path relative to the study file)")
    if ("ladder" in data) == ("sweep" in data):
        raise StudyError(f"{where}exactly one of ladder (convergence study) or sweep is required")
    scene = (path.parent / data["scene"]).resolve()
    if not scene.is_file():
        raise StudyError(f"{where}scene: {scene}: no such file")
    common = data.get("set", {}) or {}
    if not isinstance(common, dict):
        raise StudyError(f"{where}set: expected a mapping of scene keys to values")
    observables = data.get("observables", DEFAULT_OBSERVABLES)
    if not isinstance(observables, list) or not all(isinstance(o, str) for o in observables):
        raise StudyError(f"{where}observables: expected a list of observables.csv columns")
    report = data.get("report", {}) or {}
    try:
        _check_keys("report", report, REPORT_KEYS)
    except StudyError as e:
        raise StudyError(f"{where}{e}") from None
    end_state = report.get("end_state", observables)
    if not isinstance(end_state, list) or not all(isinstance(o, str) for o in end_state):
        raise StudyError(f"{where}report.end_state: expected a list of observables.csv columns")

    if "ladder" in data:
        kind, keys = "ladder", []
        members = _ladder_members(data["ladder"], scene, common, where)
    else:
        kind = "sweep"
        members, keys = _sweep_members(data["sweep"], where)
    for m in members:
        m.overrides = {**common, **m.overrides}
    names = [m.name for m in members]
    if len(set(names)) != len(names):
        raise StudyError(f"{where}two members would share the directory name {names}")
    rules = data["ladder"]["rules"] if kind == "ladder" else {}
    return Study(path, scene, (path.parent / data["output"]).resolve(), kind, members,
                 observables, end_state, keys, common, rules)
