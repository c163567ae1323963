#!/usr/bin/python3
"""Stability sweeps: error rate of each self-intersection method against one
parameter of a scenario (distance, size, angle, separation) or of a method
(epsilon, offset, guard bits). Every point is generated with `vbsim gen` and
scored with `vbsim score` (every method in one process per point, points in
parallel processes); the
results go to a CSV, one PNG chart per sweep and a markdown page naming each
method's breakdown points.

    /usr/bin/python3 scripts/sweep.py [--vbsim build/vbsim] [--only NAME ...]
                                      [--work build/sweeps] [--out docs/results]
                                      [--jobs N] [--list]

The sweeps are defined in scripts/sweep_definitions.py. Output:
    OUT/sweep-NAME.png      one line per method, errors per ray against the parameter
    OUT/sweeps.csv          every point: sweep, x, method, secondary rays and their verdict
                            counts, camera rays and the camera rays missed
Error rates are of secondary rays (every ray that leaves a surface); camera rays
are counted apart (a conservative tester misses some: the price of its bound).
    OUT/stability.md        generated: each sweep's chart and breakdown points
"""
import argparse
import csv
import glob
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import sweep_definitions
from pareto import ops_per_ray
from sweep_charts import plot_sweep, breakdown_text

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VERDICTS = ("correct", "self_hit", "false_hit", "missed", "unscored")


def run(cmd):
    """Runs a vbsim command; a failure stops the sweep with its message."""
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"sweep: command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
    return proc.stdout


def format_value(v):
    return f"{v:.9g}" if isinstance(v, float) else str(v)


def generate_point(vbsim, sweep, x, workdir):
    """Generates the scenario of one sweep point; returns its trace files."""
    out = os.path.join(workdir, sweep["name"], f"x{format_value(x)}")
    marker = os.path.join(out, ".complete")
    settings = dict(sweep.get("set", {}))
    if "key" in sweep:
        settings[sweep["key"]] = x
        if "pair" in sweep:  # a range setting pinned to one value: min = max = x
            settings[sweep["pair"]] = x
    cmd = [vbsim, "gen", sweep["scenario"], "--rays", str(sweep.get("rays", 200)),
           "--seed", str(sweep.get("seed", 1)), "-o", out]
    for k, v in sorted(settings.items()):
        cmd += ["--set", f"{k}={format_value(v)}"]
    # Regenerate unless the same command already completed into this folder.
    if not (os.path.exists(marker) and open(marker).read() == " ".join(cmd)):
        run(cmd)
        with open(marker, "w") as f:
            f.write(" ".join(cmd))
    traces = sorted(glob.glob(os.path.join(out, sweep.get("traces", "*.jsonl"))))
    if not traces:
        sys.exit(f"sweep {sweep['name']}: no trace written in {out}")
    return traces


def method_spec(method, x):
    """The `vbsim score` method entry of a method at sweep value x ('{x}' replaced)."""
    return method["spec"].replace("{x}", format_value(x))


def score_point(vbsim, sweep, x, traces):
    """Scores every method of the sweep on one point's traces, in one process."""
    folder = os.path.dirname(traces[0])
    specs = [method_spec(m, x) for m in sweep["methods"]]
    out = os.path.join(folder, "score.json")
    run([vbsim, "score", *traces, "-q", "--threads", "1", "--testers", sweep.get("tester", "three-half-plane"),
         "--methods", ",".join(specs), "--out", out])
    with open(out) as f:
        rows = json.load(f)["rows"]
    result = []
    for m, spec in zip(sweep["methods"], specs):
        mine = [r for r in rows if r["method"] == spec]
        alls = [r for r in mine if r["kind"] == "all"]
        if len(alls) != len(traces):
            sys.exit(f"sweep {sweep['name']}: score gave {len(alls)} rows for {spec}, expected {len(traces)}")
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


def run_sweep(vbsim, sweep, workdir, jobs):
    """Rows of (x, method label, verdict counts summed over the point's traces)."""
    def point(x):
        return score_point(vbsim, sweep, x, generate_point(vbsim, sweep, x, workdir))
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        return [row for rows in pool.map(point, sweep["values"]) for row in rows]


def write_markdown(path, sweeps, rows_by_sweep, command):
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
        f.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--only", nargs="*", help="run only these sweeps")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "sweeps"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "results"))
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--list", action="store_true", help="list the sweeps and exit")
    args = ap.parse_args()

    scenarios = set(run([args.vbsim, "scenarios", "--names"]).split())
    sweeps = [s for s in sweep_definitions.SWEEPS if s["scenario"] in scenarios]
    if args.list:
        for s in sweep_definitions.SWEEPS:
            state = "" if s in sweeps else "  (scenario not in this build)"
            print(f"{s['name']:<24} {s['title']}{state}")
        return
    if args.only:
        unknown = set(args.only) - {s["name"] for s in sweep_definitions.SWEEPS}
        if unknown:
            sys.exit(f"sweep: unknown sweep(s) {', '.join(sorted(unknown))}; see --list")
        sweeps = [s for s in sweeps if s["name"] in args.only]
    os.makedirs(args.out, exist_ok=True)
    rows_by_sweep = {}
    for sweep in sweeps:
        print(f"sweep {sweep['name']}: {len(sweep['values'])} points x "
              f"{len(sweep['methods'])} methods", file=sys.stderr)
        rows = run_sweep(args.vbsim, sweep, args.work, args.jobs)
        rows_by_sweep[sweep["name"]] = rows
        plot_sweep(sweep, rows, os.path.join(args.out, f"sweep-{sweep['name']}.png"))
    csv_path = os.path.join(args.out, "sweeps.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["sweep", "x", "method", "rays", "ops_per_ray", *VERDICTS,
                                          "camera_rays", "camera_missed"])
        w.writeheader()
        for sweep in sweeps:
            for row in sorted(rows_by_sweep[sweep["name"]], key=lambda r: (r["method"], r["x"])):
                w.writerow(row)
    command = "/usr/bin/python3 scripts/sweep.py" + (
        " --only " + " ".join(args.only) if args.only else "")
    write_markdown(os.path.join(args.out, "stability.md"), sweeps, rows_by_sweep, command)
    print(f"sweep: wrote {csv_path}, stability.md and {len(sweeps)} charts", file=sys.stderr)


if __name__ == "__main__":
    main()
