#!/usr/bin/python3
"""Stability sweeps: error rate of each self-intersection method against one
parameter of a scenario (distance, size, angle, separation) or of a method
(epsilon, offset, guard bits). Every point is generated with `vbsim gen` and
scored with `vbsim score` (every method in one process per point); the points
run in parallel on local cores or as one Slurm job array (point_jobs.py,
docs/cluster.md) and are cached by content. The results go to a CSV, one PNG
chart per sweep and a markdown page naming each method's breakdown points.

    /usr/bin/python3 scripts/sweep.py [--vbsim build/vbsim] [--only NAME ...] [--definition FILE]
                                      [--work build/sweeps] [--out docs/results]
                                      [--jobs N] [--fresh] [--list]
                                      [--backend slurm [--partition P] [--account A]
                                       [--time T] [--max-parallel N]]

The sweeps are defined in scripts/sweep_definitions.py (or a JSON list of sweeps
in the same form, --definition). Output:
    OUT/sweep-NAME.png      one line per method, errors per ray against the parameter
    OUT/sweeps.csv          every point: sweep, x, method, secondary rays and their verdict
                            counts, camera rays and the camera rays missed
                            (after a '#' line with the provenance)
Error rates are of secondary rays (every ray that leaves a surface); camera rays
are counted apart (a conservative tester misses some: the price of its bound).
    OUT/stability.md        generated: each sweep's chart and breakdown points
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import sweep_definitions
from pareto import ops_per_ray
from point_jobs import Point, add_backend_arguments, check_backend_arguments, content_key, file_digest, run_points
import provenance
from sweep_charts import plot_sweep, breakdown_text

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VERDICTS = ("correct", "self_hit", "false_hit", "missed", "unscored")
# Scenarios that read the bundled bunny unless `scene=` names another mesh.
BUNNY = os.path.join(ROOT, "traces", "bunny", "bunny.obj")
BUNNY_SCENARIOS = ("paths", "far-instance")


def run(cmd):
    """Runs a vbsim command; a failure stops the sweep with its message."""
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"sweep: command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
    return proc.stdout


def format_value(v):
    return f"{v:.9g}" if isinstance(v, float) else str(v)


def method_spec(method, x):
    """The `vbsim score` method entry of a method at sweep value x ('{x}' replaced)."""
    return method["spec"].replace("{x}", format_value(x))


def point_settings(sweep, x):
    settings = dict(sweep.get("set", {}))
    if "key" in sweep:
        settings[sweep["key"]] = x
        if "pair" in sweep:  # a range setting pinned to one value: min = max = x
            settings[sweep["pair"]] = x
    return settings


def sweep_point(vbsim, sweep, x, cache):
    """One point: `vbsim gen` into the cache, then `vbsim score` of its traces with
    every method of the sweep, in one process. The key hashes the binary, both
    command lines and the mesh the scenario reads."""
    settings = point_settings(sweep, x)
    gen = ["gen", sweep["scenario"], "--rays", str(sweep.get("rays", 200)), "--seed", str(sweep.get("seed", 1))]
    for k, v in sorted(settings.items()):
        gen += ["--set", f"{k}={format_value(v)}"]
    score = ["score", "-q", "--threads", "1", "--testers", sweep.get("tester", "three-half-plane"),
             "--methods", ",".join(method_spec(m, x) for m in sweep["methods"])]
    mesh = settings.get("scene", BUNNY if sweep["scenario"] in BUNNY_SCENARIOS else None)
    mesh_digest = file_digest(mesh if os.path.isabs(mesh) else os.path.join(ROOT, mesh)) if mesh else None
    pattern = sweep.get("traces", "*.jsonl")
    key = content_key(vbsim=file_digest(vbsim), gen=gen, traces=pattern, score=score, mesh=mesh_digest)
    folder = os.path.join(cache, key + ".gen")
    result = os.path.join(cache, key + ".score.json")
    commands = [[vbsim, *gen, "-q", "-o", folder],
                [vbsim, score[0], {"glob": os.path.join(folder, pattern)}, *score[1:], "--out", result + ".part"]]
    return Point(f"{sweep['name']} x={format_value(x)}", commands, result)


def point_rows(sweep, x, score):
    """Rows of (x, method label, verdict counts summed over the point's traces)."""
    traces = len(score["families"])  # every trace given to vbsim score is a family of its own
    result = []
    for m in sweep["methods"]:
        spec = method_spec(m, x)
        mine = [r for r in score["rows"] if r["method"] == spec]
        alls = [r for r in mine if r["kind"] == "all"]
        if len(alls) != traces:
            sys.exit(f"sweep {sweep['name']}: score gave {len(alls)} rows for {spec}, expected {traces}")
        row = {"sweep": sweep["name"], "x": x, "method": m["label"], "rays": 0, "ops_per_ray": 0.0,
               **{v: 0 for v in VERDICTS}, "camera_rays": 0, "camera_missed": 0}
        all_rays = 0
        for r in alls:
            all_rays += r["rays"]
            row["ops_per_ray"] += ops_per_ray(r) * r["rays"]
        for r in mine:
            if r["kind"] == "secondary":
                row["rays"] += r["rays"]
                for v in VERDICTS:
                    row[v] += r["counts"][v]
            elif r["kind"] == "primary":
                row["camera_rays"] += r["rays"]
                row["camera_missed"] += r["counts"]["missed"]
        row["ops_per_ray"] = row["ops_per_ray"] / all_rays if all_rays else 0.0
        result.append(row)
    return result


def write_markdown(path, sweeps, rows_by_sweep, command, prov):
    lines = ["# Stability sweeps", "",
             "Generated by `scripts/sweep.py`; do not edit by hand. Regenerate with:", "",
             f"    {command}", "",
             "Each point is a scenario generated with `vbsim gen` (exact expectations from the "
             "oracle) and replayed with each method. Errors per ray = (self_hit + false_hit + "
             "missed) / scored secondary rays (every ray that leaves a surface); camera rays are "
             "counted apart, in the last column. A point with no error is drawn on the chart's "
             "floor line.", ""]
    for sweep in sweeps:
        rows = rows_by_sweep[sweep["name"]]
        lines += [f"## {sweep['title']}", "", sweep.get("about", ""), "",
                  f"![{sweep['name']}](sweep-{sweep['name']}.png)", ""]
        lines += breakdown_text(sweep, rows)
        lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n" + provenance.provenance_comment(prov))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--only", nargs="*", help="run only these sweeps")
    ap.add_argument("--definition", help="JSON list of sweeps (default: sweep_definitions.SWEEPS)")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "sweeps"), help="cached points")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "results"))
    ap.add_argument("--list", action="store_true", help="list the sweeps and exit")
    add_backend_arguments(ap)
    args = ap.parse_args()
    check_backend_arguments(ap, args)
    if not os.path.exists(args.vbsim):
        sys.exit(f"sweep: no vbsim binary at {args.vbsim} (build with scripts/setup.sh)")
    vbsim = os.path.abspath(args.vbsim)

    defined = sweep_definitions.SWEEPS
    if args.definition:
        with open(args.definition) as f:
            defined = json.load(f)
    scenarios = set(run([vbsim, "scenarios", "--names"]).split())
    sweeps = [s for s in defined if s["scenario"] in scenarios]
    if args.list:
        for s in defined:
            state = "" if s in sweeps else "  (scenario not in this build)"
            print(f"{s['name']:<24} {s['title']}{state}")
        return
    if args.only:
        unknown = set(args.only) - {s["name"] for s in defined}
        if unknown:
            sys.exit(f"sweep: unknown sweep(s) {', '.join(sorted(unknown))}; see --list")
        sweeps = [s for s in sweeps if s["name"] in args.only]
    for sweep in sweeps:
        print(f"sweep {sweep['name']}: {len(sweep['values'])} points x {len(sweep['methods'])} methods",
              file=sys.stderr)
    cache = os.path.join(args.work, "points")
    where = [(sweep, x) for sweep in sweeps for x in sweep["values"]]
    points = [sweep_point(vbsim, sweep, x, cache) for sweep, x in where]
    scores = run_points(points, args, args.work, "sweep")
    rows_by_sweep = {sweep["name"]: [] for sweep in sweeps}
    for (sweep, x), score in zip(where, scores):
        rows_by_sweep[sweep["name"]] += point_rows(sweep, x, score)
    prov = provenance.script_provenance(vbsim, [p.result for p in points])

    os.makedirs(args.out, exist_ok=True)
    for sweep in sweeps:
        chart = os.path.join(args.out, f"sweep-{sweep['name']}.png")
        plot_sweep(sweep, rows_by_sweep[sweep["name"]], chart)
        provenance.stamp_png(chart, prov)
    csv_path = os.path.join(args.out, "sweeps.csv")
    with open(csv_path, "w", newline="") as f:
        f.write(provenance.csv_comment(prov))
        w = csv.DictWriter(f, fieldnames=["sweep", "x", "method", "rays", "ops_per_ray", *VERDICTS,
                                          "camera_rays", "camera_missed"])
        w.writeheader()
        for sweep in sweeps:
            for row in sorted(rows_by_sweep[sweep["name"]], key=lambda r: (r["method"], r["x"])):
                w.writerow(row)
    command = "/usr/bin/python3 scripts/sweep.py" + (
        f" --definition {args.definition}" if args.definition else "") + (
        " --only " + " ".join(args.only) if args.only else "")
    write_markdown(os.path.join(args.out, "stability.md"), sweeps, rows_by_sweep, command, prov)
    print(f"sweep: wrote {csv_path}, stability.md and {len(sweeps)} charts", file=sys.stderr)


if __name__ == "__main__":
    main()
