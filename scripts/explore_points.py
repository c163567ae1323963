"""The points of an exploration and the rows they give (`vbsim explore`,
docs/explore.md).

A point is one (workload, method, design, technology file): one cycle-level
`vbsim replay` of the workload's trace, or one closed-loop `vbsim render`
of its frame, with the design's configuration; its statistics JSON is the
point's result, cached under DIR/points/ by a key over everything it depends
on (the vbsim binary's bytes, the trace's or scene's bytes, the method, the
configuration, the technology file's bytes), so a rerun skips finished points.

A row holds what points.csv gives for the point: the design's parameters as
run (read back from the statistics' `config.hw`), area, energy per ray,
cycles per ray, Mrays/s at the design's clock, Mrays/J, and the secondary
rays' error rate with its 95% Wilson interval.
"""
import glob
import math
import os
import subprocess

from arch_points import merge, set_path
from explore_definition import knob_label
from point_jobs import Point, content_key, file_digest, write_json_once

CAMERA_KINDS = ("primary", "camera")
ERRORS = ("self_hit", "false_hit", "missed")


class ExploreError(Exception):
    pass


def resolve(root, path):
    return path if os.path.isabs(path) else os.path.join(root, path)


def run_checked(argv):
    proc = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise ExploreError(f"command failed ({proc.returncode}): {' '.join(argv)}\n{proc.stderr.strip()}")
    return proc.stdout


def prepare_workload(vbsim, root, work, w):
    """The workload with its input file(s) ready: `input` (a trace, or a render's scene)."""
    if w["kind"] == "render":
        scene = resolve(root, w["render"]["scene"])
        if not os.path.exists(scene):
            raise ExploreError(f"workload '{w['name']}': scene '{w['render']['scene']}' does not exist")
        return {**w, "input": scene}
    if w["kind"] == "trace":
        trace = resolve(root, w["trace"])
        if not os.path.exists(trace):
            raise ExploreError(f"workload '{w['name']}': trace '{w['trace']}' does not exist")
    else:  # a scenario, generated once
        rays, seed = w.get("rays", 2000), w.get("seed", 1)
        out = os.path.join(work, "traces", f"{w['scenario']}-{rays}-seed{seed}")
        marker = os.path.join(out, ".complete")
        cmd = ["gen", w["scenario"], "--rays", str(rays), "--seed", str(seed)]
        if not (os.path.exists(marker) and open(marker).read() == " ".join(cmd)):
            run_checked([vbsim, *cmd, "-o", out])
            with open(marker, "w") as f:
                f.write(" ".join(cmd))
        found = sorted(glob.glob(os.path.join(out, w.get("pick", "*") + ".jsonl")))
        if len(found) != 1:
            names = ", ".join(os.path.basename(t)[:-6] for t in sorted(glob.glob(os.path.join(out, "*.jsonl"))))
            raise ExploreError(f"workload '{w['name']}': scenario '{w['scenario']}' has {len(found)} traces matching "
                               f"'{w.get('pick', '*')}' (of {names}); `pick` names one")
        trace = found[0]
    if w.get("oracle"):  # fill in the exact answers once (a capture has none)
        ext = os.path.splitext(trace)[1]
        scored = os.path.join(work, "traces", f"oracle-{file_digest(trace)[:16]}{ext}")
        if not os.path.exists(scored):
            os.makedirs(os.path.dirname(scored), exist_ok=True)
            part = os.path.join(work, "traces", f"oracle-{file_digest(trace)[:16]}.part{ext}")
            run_checked([vbsim, "oracle", "-q", trace, "-o", part])
            os.replace(part, scored)
        trace = scored
    return {**w, "input": trace}


def design_hw(definition, knobs):
    hw = merge({"preset": definition["preset"]}, definition["base"])
    for knob, value in knobs.items():
        hw = set_path(hw, knob, value)
    return hw


def make_point(vbsim, root, work, out_dir, definition, w, m, knobs, tech):
    hw = design_hw(definition, knobs)
    tech_path = resolve(root, tech)
    if not os.path.exists(tech_path):
        raise ExploreError(f"technology file '{tech}' does not exist")
    key = content_key(vbsim=file_digest(vbsim), input=file_digest(w["input"]), workload=w, method=m, hw=hw,
                      tech=file_digest(tech_path))
    config = os.path.join(work, "configs", key + ".json")
    os.makedirs(os.path.dirname(config), exist_ok=True)
    write_json_once(config, {"hw": hw})
    result = os.path.join(out_dir, "points", key + ".json")
    common = ["--mode", "cycle", "-q", "-m", m["method"], "--tester", m["tester"], "--config", config,
              "--tech", tech_path, "--stats", result + ".part"]
    if w["kind"] == "render":
        r = w["render"]
        cmd = [vbsim, "render", w["input"], "-o", os.path.join(work, "images", key + ".png"),
               "--integrator", r.get("integrator", "path"), "--size", r.get("size", "64x48")]
        for field, option in (("spp", "--spp"), ("bounces", "--bounces"), ("seed", "--seed"), ("light", "--light"),
                              ("camera", "--camera"), ("children_from", "--children-from")):
            if field in r:
                cmd += [option, str(r[field])]
        os.makedirs(os.path.join(work, "images"), exist_ok=True)
    else:
        cmd = [vbsim, "replay", w["input"]]
    label = f"{w['name']} / {m['name']} / {knob_label(knobs)} / {os.path.basename(tech)}"
    return Point(label, [cmd + common], result)


def wilson(errors, n, z=1.959964):
    """The 95% Wilson score interval of errors/n, per million: (low, high)."""
    if n == 0:
        return (math.nan, math.nan)
    p = errors / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return (max(0.0, centre - half) * 1e6, min(1.0, centre + half) * 1e6)


def verdict_counts(stats, secondary):
    errors = scored = unscored = 0
    for kind, k in stats.get("by_kind", {}).items():
        if (kind in CAMERA_KINDS) == secondary:
            continue
        v = k["verdicts"]
        errors += sum(v[e] for e in ERRORS)
        scored += v["correct"] + sum(v[e] for e in ERRORS)
        unscored += v.get("unscored", 0)
    return errors, scored, unscored


def get_path(d, dotted):
    for part in dotted.split("."):
        if not isinstance(d, dict) or part not in d:
            return None
        d = d[part]
    return d


def row_of(stats, w, m, knobs, tech, knob_names):
    hw = stats["hw"]
    rays, cycles = hw["rays"], hw["cycles"]
    errors, scored, unscored = verdict_counts(stats, secondary=True)
    cam_errors, cam_scored, _ = verdict_counts(stats, secondary=False)
    low, high = wilson(errors, scored)
    energy = hw.get("energy") or {}
    row = {"workload": w["name"], "method": m["name"], "design": knob_label(knobs),
           "tech": os.path.splitext(os.path.basename(tech))[0]}
    for knob in knob_names:  # as run: the preset's value where the design leaves the knob alone
        value = get_path(stats["config"]["hw"], knob)
        row[knob] = value if value is not None else knobs.get(knob)
    row.update({
        "area_mm2": hw["area"]["chip_mm2"],
        "energy_pj_per_ray": energy.get("per_ray_pj"),
        "cycles_per_ray": cycles / rays if rays else math.nan,
        "mrays_per_s": hw["rays_per_s"] / 1e6,
        "mrays_per_j": energy.get("mrays_per_j"),
        "errors_per_million": errors / scored * 1e6 if scored else math.nan,
        "ci95_low": low, "ci95_high": high,
        "secondary_scored": scored, "secondary_unscored": unscored,
        "camera_errors_per_million": cam_errors / cam_scored * 1e6 if cam_scored else math.nan,
        "rays": rays, "cycles": cycles,
    })
    return row


def dominates(a, b, axes):
    return all(a[x] <= b[x] for x in axes) and any(a[x] < b[x] for x in axes)


def mark_pareto(rows, axes=("area_mm2", "energy_pj_per_ray", "cycles_per_ray")):
    """pareto = 1 where no design of the same workload, method and technology file beats the row on every axis."""
    groups = {}
    for r in rows:
        groups.setdefault((r["workload"], r["method"], r["tech"]), []).append(r)
    for group in groups.values():
        for r in group:
            r["pareto"] = int(not any(dominates(o, r, axes) for o in group if o is not r))
