"""The definition of a design-space exploration (`vbsim explore`, docs/explore.md):
read, checked field by field (errors name the file and the field), and expanded
into its workloads, methods, designs and technology files.

A design is the preset, then `base`, then one value for each knob it sets
(a knob is a dotted path into the `hw` object: "avoidance.share",
"shader.cores"). Designs come from any of:
  grid    every combination of the knobs' values (a Cartesian product);
  list    each entry one design (an object of knob: value);
  random  `samples` designs drawn from `space` (knob: [values]) with `seed`,
          without repeats (fewer when the space holds fewer).
Their union, in that order, without repeats; no design source: the preset alone.
"""
import itertools
import json
import random

METHOD_FIELDS = {"name", "method", "tester"}
WORKLOAD_KINDS = ("trace", "scenario", "render")
RENDER_FIELDS = {"scene", "size", "integrator", "spp", "bounces", "seed", "light", "camera", "children_from"}


class DefinitionError(Exception):
    pass


def fail(path, field, why):
    raise DefinitionError(f"{path}: field '{field}': {why}")


def knob_label(knobs):
    """A design's name: its knobs in order, `key=value` joined by spaces ('preset' alone: none)."""
    return " ".join(f"{k}={json.dumps(v)}" for k, v in knobs.items()) or "preset"


def check_knob(path, where, knob, values):
    if not isinstance(knob, str) or not knob or any(not part for part in knob.split(".")):
        fail(path, where, f"'{knob}' is not a dotted hw field (e.g. avoidance.share)")
    if knob.split(".")[0] == "preset":
        fail(path, where, "the preset is the definition's `preset`, not a knob")
    if not isinstance(values, list) or not values:
        fail(path, f"{where}.{knob}", "must be a non-empty list of values")


def expand_designs(path, spec):
    """The designs of `spec` (the definition's `designs`): a list of knob dicts."""
    if spec is None:
        return [{}]
    if not isinstance(spec, dict):
        fail(path, "designs", "must be an object with grid, list and/or random")
    unknown = set(spec) - {"grid", "list", "random"}
    if unknown:
        fail(path, f"designs.{sorted(unknown)[0]}", "unknown field (grid, list, random)")
    designs = []
    if "grid" in spec:
        grid = spec["grid"]
        if not isinstance(grid, dict) or not grid:
            fail(path, "designs.grid", "must be an object of knob: [values]")
        for knob, values in grid.items():
            check_knob(path, "designs.grid", knob, values)
        keys = list(grid)
        designs += [dict(zip(keys, combo)) for combo in itertools.product(*(grid[k] for k in keys))]
    if "list" in spec:
        entries = spec["list"]
        if not isinstance(entries, list) or not entries:
            fail(path, "designs.list", "must be a non-empty list of objects (knob: value)")
        for i, d in enumerate(entries):
            if not isinstance(d, dict):
                fail(path, f"designs.list[{i}]", "must be an object of knob: value")
            for knob, value in d.items():
                check_knob(path, f"designs.list[{i}]", knob, [value])
            designs.append(dict(d))
    if "random" in spec:
        r = spec["random"]
        if not isinstance(r, dict) or set(r) - {"samples", "seed", "space"} or "space" not in r:
            fail(path, "designs.random", "must be {samples, seed, space: {knob: [values]}}")
        samples, seed = r.get("samples", 8), r.get("seed", 1)
        if not isinstance(samples, int) or samples < 1:
            fail(path, "designs.random.samples", "must be an integer >= 1")
        if not isinstance(seed, int):
            fail(path, "designs.random.seed", "must be an integer")
        space = r["space"]
        if not isinstance(space, dict) or not space:
            fail(path, "designs.random.space", "must be an object of knob: [values]")
        for knob, values in space.items():
            check_knob(path, "designs.random.space", knob, values)
        size = 1
        for values in space.values():
            size *= len(values)
        rng = random.Random(seed)
        drawn, seen = [], set()
        while len(drawn) < min(samples, size):
            d = {k: rng.choice(v) for k, v in space.items()}
            key = json.dumps(d, sort_keys=True)
            if key not in seen:
                seen.add(key)
                drawn.append(d)
        designs += drawn
    unique, seen = [], set()
    for d in designs:
        key = json.dumps(d, sort_keys=True)
        if key not in seen:
            seen.add(key)
            unique.append(d)
    return unique


def parse_method(path, i, m, default_tester):
    if isinstance(m, str):
        m = {"method": m}
    if not isinstance(m, dict) or "method" not in m:
        fail(path, f"methods[{i}]", "must be a method string or {method, tester, name}")
    unknown = set(m) - METHOD_FIELDS
    if unknown:
        fail(path, f"methods[{i}].{sorted(unknown)[0]}", "unknown field (method, tester, name)")
    tester = m.get("tester", default_tester)
    name = m.get("name") or (m["method"] if tester == "three-half-plane" else f"{m['method']} ({tester})")
    return {"name": name, "method": m["method"], "tester": tester}


def parse_workload(path, i, w):
    where = f"workloads[{i}]"
    if not isinstance(w, dict) or "name" not in w:
        fail(path, where, "must be an object with a name and one of trace, scenario, render")
    kinds = [k for k in WORKLOAD_KINDS if k in w]
    if len(kinds) != 1:
        fail(path, where, "needs exactly one of trace (a file), scenario (vbsim gen) or render (a closed-loop frame)")
    allowed = {"name", "oracle", "rays", "seed", "pick", "notes"} | set(WORKLOAD_KINDS)
    unknown = set(w) - allowed
    if unknown:
        fail(path, f"{where}.{sorted(unknown)[0]}", "unknown field")
    if kinds[0] == "render":
        r = w["render"]
        if not isinstance(r, dict) or "scene" not in r:
            fail(path, f"{where}.render", "must be an object with a scene")
        unknown = set(r) - RENDER_FIELDS
        if unknown:
            fail(path, f"{where}.render.{sorted(unknown)[0]}", f"unknown field ({', '.join(sorted(RENDER_FIELDS))})")
    if kinds[0] == "scenario" and not isinstance(w.get("rays", 0), int):
        fail(path, f"{where}.rays", "must be an integer")
    return {**w, "kind": kinds[0]}


def load_definition(path):
    """The checked definition with `workloads`, `methods`, `designs` (knob dicts), `tech` (paths)."""
    try:
        with open(path) as f:
            d = json.load(f)
    except OSError as e:
        raise DefinitionError(f"{path}: {e.strerror}")
    except json.JSONDecodeError as e:
        raise DefinitionError(f"{path}: line {e.lineno}: not JSON ({e.msg})")
    if not isinstance(d, dict):
        fail(path, "<root>", "must be an object")
    known = {"name", "preset", "base", "workloads", "methods", "tester", "designs", "tech", "area_budgets_mm2",
             "throughput_targets_mrays_per_s", "notes"}
    unknown = set(d) - known
    if unknown:
        fail(path, sorted(unknown)[0], f"unknown field ({', '.join(sorted(known))})")
    for field in ("workloads", "methods"):
        if not isinstance(d.get(field), list) or not d[field]:
            fail(path, field, "must be a non-empty list")
    workloads = [parse_workload(path, i, w) for i, w in enumerate(d["workloads"])]
    names = [w["name"] for w in workloads]
    if len(set(names)) != len(names):
        fail(path, "workloads", "two workloads share a name")
    tester = d.get("tester", "three-half-plane")
    methods = [parse_method(path, i, m, tester) for i, m in enumerate(d["methods"])]
    if len({m["name"] for m in methods}) != len(methods):
        fail(path, "methods", "two methods share a name (give each a `name`)")
    base = d.get("base", {})
    if not isinstance(base, dict):
        fail(path, "base", "must be an hw object")
    tech = d.get("tech", ["model/energy/tech/45nm.json"])
    if isinstance(tech, str):
        tech = [tech]
    if not isinstance(tech, list) or not tech or not all(isinstance(t, str) for t in tech):
        fail(path, "tech", "must be a technology file or a list of them")
    for field in ("area_budgets_mm2", "throughput_targets_mrays_per_s"):
        v = d.get(field, [])
        if not isinstance(v, list) or not all(isinstance(x, (int, float)) and x > 0 for x in v):
            fail(path, field, "must be a list of positive numbers")
    return {"name": d.get("name", "explore"), "preset": d.get("preset", "small"), "base": base,
            "workloads": workloads, "methods": methods, "designs": expand_designs(path, d.get("designs")),
            "tech": tech, "area_budgets_mm2": d.get("area_budgets_mm2", []),
            "throughput_targets_mrays_per_s": d.get("throughput_targets_mrays_per_s", [])}
