#!/usr/bin/python3
"""Design-space exploration: every (workload, method, design, technology file)
of a definition through the cycle-level model, then each method's Pareto
front, iso-area and iso-throughput comparisons and each knob's sensitivity.
Run as `vbsim explore DEFINITION.json -o DIR` (docs/explore.md).

    vbsim explore DEFINITION.json -o DIR [--jobs N] [--fresh]
        [--backend slurm [--partition P] [--account A] [--time T] [--max-parallel N]]

Output:
    DIR/points.csv       one row per (workload, method, design, technology file)
    DIR/report.md        fronts, iso-area, iso-throughput, sensitivity (with charts)
    DIR/points/KEY.json  each point's statistics, the cache that makes a rerun resume
The points run in parallel on local processes or as one Slurm job array
(point_jobs.py); finished points are not rerun.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import explore_definition  # noqa: E402
import explore_points  # noqa: E402
import explore_report  # noqa: E402
from point_jobs import add_backend_arguments, check_backend_arguments, run_points  # noqa: E402
import provenance  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIGURES = ["area_mm2", "energy_pj_per_ray", "cycles_per_ray", "mrays_per_s", "mrays_per_j", "errors_per_million",
           "ci95_low", "ci95_high", "camera_errors_per_million", "secondary_scored", "secondary_unscored", "rays",
           "cycles", "pareto"]


def write_csv(path, rows, knobs, prov):
    columns = ["workload", "method", "design", "tech", "preset"] + knobs + FIGURES
    with open(path + ".part", "w", newline="") as f:
        f.write(provenance.csv_comment(prov))
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if isinstance(v, float) and math.isnan(v) else v) for k, v in r.items()})
    os.replace(path + ".part", path)


def main():
    ap = argparse.ArgumentParser(prog="vbsim explore", description=__doc__.split("\n")[0])
    ap.add_argument("definition", help="the exploration's definition (JSON, docs/explore.md)")
    ap.add_argument("-o", "--out", required=True, help="output directory: points.csv, report.md, points/")
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"), help=argparse.SUPPRESS)
    ap.add_argument("--list", action="store_true", help="print the points and exit")
    add_backend_arguments(ap)
    args = ap.parse_args()
    check_backend_arguments(ap, args)
    try:
        definition = explore_definition.load_definition(args.definition)
    except explore_definition.DefinitionError as e:
        sys.exit(f"vbsim explore: error: {e}")
    vbsim = os.path.abspath(args.vbsim)
    if not os.path.exists(vbsim):
        sys.exit(f"vbsim explore: error: no vbsim program at {vbsim}")
    out = os.path.abspath(args.out)
    work = os.path.join(out, "work")
    os.makedirs(work, exist_ok=True)
    try:
        workloads = [explore_points.prepare_workload(vbsim, ROOT, work, w) for w in definition["workloads"]]
        plan = [(w, m, knobs, tech) for w in workloads for m in definition["methods"]
                for knobs in definition["designs"] for tech in definition["tech"]]
        points = [explore_points.make_point(vbsim, ROOT, work, out, definition, *p) for p in plan]
    except explore_points.ExploreError as e:
        sys.exit(f"vbsim explore: error: {e}")
    if args.list:
        for p in points:
            print(p.label)
        return
    stats = run_points(points, args, work, "vbsim explore")
    knobs = list(dict.fromkeys(k for d in definition["designs"] for k in d))
    rows = [explore_points.row_of(s, w, m, knobs_of, tech, knobs) for s, (w, m, knobs_of, tech) in zip(stats, plan)]
    for r in rows:
        r["preset"] = definition["preset"]
    explore_points.mark_pareto(rows)
    prov = provenance.script_provenance(vbsim, [w["input"] for w in workloads] + [args.definition])
    write_csv(os.path.join(out, "points.csv"), rows, knobs, prov)
    command = f"vbsim explore {os.path.relpath(args.definition, ROOT) if args.definition.startswith(ROOT) else args.definition} -o {args.out}"
    explore_report.write_report(out, definition, rows, knobs, prov, command)
    unscored = sorted({r["workload"] for r in rows if r["secondary_scored"] == 0})
    if unscored:
        print(f"vbsim explore: warning: no scored secondary rays in {', '.join(unscored)} (a trace without "
              "expectations: set \"oracle\": true on the workload)", file=sys.stderr)
    print(f"vbsim explore: {len(rows)} points -> {out}/points.csv, {out}/report.md", file=sys.stderr)


if __name__ == "__main__":
    main()
