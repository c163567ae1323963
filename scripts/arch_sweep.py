#!/usr/bin/python3
"""Architecture studies with the cycle-level model: sweeps over cores, ray slots,
pipeline latencies, cache sizes, DRAM latency and bandwidth and methods; the
presets' predictions; and each method's cost in cycles on every scenario family.
Every point is an independent `vbsim replay --mode cycle --config POINT.json
--stats OUT.json` process, run in parallel on local cores or as one Slurm job
array (point_jobs.py, docs/cluster.md); finished points are cached by content.

    /usr/bin/python3 scripts/arch_sweep.py [--vbsim build/vbsim] [--definition FILE]
        [--only NAME ...] [--work build/arch] [--out docs/results]
        [--results build/results] [--jobs N] [--fresh] [--list]
        [--backend slurm [--partition P] [--account A] [--time T] [--max-parallel N]]

Output:
    OUT/arch-GROUP.png              one chart per sweep group
    OUT/architecture.md             generated: charts, tables, what limits throughput
    RESULTS/arch_sweep.json         every point's figures
    RESULTS/method_cycles.json      per (family, method): rays, cycles, cycles per ray, latency
The default definition is in scripts/arch_sweep_definitions.py.
"""
import argparse
import glob
import json
import os
import subprocess
import sys

import arch_families
from arch_charts import CHARTS
from arch_points import arch_point, merge, set_path, summarise
import arch_report
import arch_sweep_definitions
from point_jobs import add_backend_arguments, check_backend_arguments, run_points
import provenance

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(cmd):
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"arch_sweep: command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
    return proc.stdout


def trace_file(vbsim, work, spec):
    """The trace of a definition's `trace` entry: a file, or a scenario generated once."""
    if "file" in spec:
        path = spec["file"] if os.path.isabs(spec["file"]) else os.path.join(ROOT, spec["file"])
        if not os.path.exists(path):
            sys.exit(f"arch_sweep: trace '{spec['file']}' does not exist")
        return path
    out = os.path.join(work, "traces", f"{spec['scenario']}-{spec['rays']}-seed{spec['seed']}")
    marker = os.path.join(out, ".complete")
    cmd = ["gen", spec["scenario"], "--rays", str(spec["rays"]), "--seed", str(spec["seed"])]
    if not (os.path.exists(marker) and open(marker).read() == " ".join(cmd)):
        run([vbsim, *cmd, "-o", out])
        with open(marker, "w") as f:
            f.write(" ".join(cmd))
    traces = sorted(glob.glob(os.path.join(out, "*.jsonl")))
    if len(traces) != 1:
        sys.exit(f"arch_sweep: scenario '{spec['scenario']}' wrote {len(traces)} traces; a sweep needs one")
    return traces[0]


def resolve_series(definition, sweep):
    series = sweep["series"]
    if isinstance(series, str):
        if series not in definition.get("series", {}):
            sys.exit(f"arch_sweep: sweep '{sweep['name']}': unknown series list '{series}'")
        series = definition["series"][series]
    return {**sweep, "series": series}


def sweep_points(definition, sweeps, trace):
    """Points and their (sweep, series, x) labels."""
    points, labels = [], []
    for sweep in sweeps:
        for s in sweep["series"]:
            method = s.get("method", sweep.get("method", definition.get("method", "none")))
            hw = merge({"preset": sweep.get("preset", "small")}, s.get("hw", {}))
            for x in sweep["values"]:
                if sweep["x"] == "method":
                    points.append((trace, {"hw": hw}, x))
                else:
                    points.append((trace, {"hw": set_path(hw, sweep["x"], x)}, method))
                labels.append({"sweep": sweep["name"], "series": s["label"], "x": x})
    return points, labels


def preset_points(vbsim, work, definition, sweep_trace):
    spec = definition.get("presets")
    if not spec:
        return [], []
    points, labels = [], []
    method = definition.get("method", "none")
    for preset in spec["presets"]:
        for name, tspec in spec["traces"].items():
            trace = sweep_trace if tspec == "sweep" else trace_file(vbsim, work, tspec)
            for ideal in (False, True):
                for deps in (True, False):
                    points.append((trace, {"hw": {"preset": preset, "memory": {"ideal": ideal},
                                                  "source": {"dependencies": deps}}}, method))
                    labels.append({"preset": preset, "trace": name})
    return points, labels


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--definition", help="JSON sweep definition (default: arch_sweep_definitions.DEFAULT)")
    ap.add_argument("--only", nargs="*", help="run only these sweeps (and no presets or families)")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "arch"), help="traces and cached points")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "results"), help="charts and architecture.md")
    ap.add_argument("--results", default=os.path.join(ROOT, "build", "results"), help="JSON results")
    ap.add_argument("--families", nargs="*",
                    help="measure the methods' cycles on these scenario folders (as scored by vbsim score, "
                         "so the rows join with its table) instead of small generated ones")
    ap.add_argument("--list", action="store_true", help="list the sweeps and exit")
    add_backend_arguments(ap)
    args = ap.parse_args()
    check_backend_arguments(ap, args)

    if args.definition:
        with open(args.definition) as f:
            definition = json.load(f)
    else:
        definition = arch_sweep_definitions.DEFAULT
    sweeps = [resolve_series(definition, s) for s in definition["sweeps"]]
    if args.list:
        for s in sweeps:
            print(f"{s['name']:<20} {len(s['values'])} x {len(s['series'])} points  {s['title']}")
        return
    if args.only is not None:
        unknown = set(args.only) - {s["name"] for s in sweeps}
        if unknown:
            sys.exit(f"arch_sweep: unknown sweep(s) {', '.join(sorted(unknown))}; see --list")
        sweeps = [s for s in sweeps if s["name"] in args.only]
        definition = {**definition, "presets": None, "families": None}
    if not os.path.exists(args.vbsim):
        sys.exit(f"arch_sweep: no vbsim binary at {args.vbsim} (build with scripts/setup.sh)")
    vbsim = os.path.abspath(args.vbsim)
    cache = os.path.join(args.work, "points")

    trace = trace_file(vbsim, args.work, definition["trace"])
    points, labels = sweep_points(definition, sweeps, trace)
    p_points, p_labels = preset_points(vbsim, args.work, definition, trace)
    family_spec = definition.get("families")
    families, f_points, f_labels = [], [], []
    if family_spec:
        scenarios = family_spec.get("scenarios") or run([vbsim, "scenarios", "--names"]).split()
        families = arch_families.family_traces(run, vbsim, args.work, family_spec, scenarios, ROOT,
                                               args.families)
        f_points, f_labels = arch_families.family_points(families, family_spec)
    everything = points + p_points + f_points
    print(f"arch_sweep: {len(everything)} points ({len(points)} sweep, {len(p_points)} preset, "
          f"{len(f_points)} family)", file=sys.stderr)
    stats = run_points([arch_point(vbsim, cache, *p) for p in everything], args, args.work, "arch_sweep")
    summaries = [summarise(s) for s in stats]
    traces_used = sorted({p[0] for p in everything})
    prov = provenance.script_provenance(vbsim, traces_used)

    rows = [{**label, **s} for label, s in zip(labels, summaries[:len(points)])]
    preset_rows = [{**label, **s} for label, s in zip(p_labels, summaries[len(points):len(points) + len(p_points)])]
    family_rows = arch_families.family_rows(families, family_spec, f_labels,
                                            summaries[len(points) + len(p_points):]) if family_spec else []

    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.results, exist_ok=True)
    groups = {}
    for s in sweeps:
        groups.setdefault(s.get("group", s["name"]), []).append(s)
    sections = []
    for group, members in groups.items():
        image = f"arch-{group}.png"
        CHARTS[members[0]["chart"]](members, rows, os.path.join(args.out, image))
        provenance.stamp_png(os.path.join(args.out, image), prov)
        if members[0]["chart"] == "methods":
            sections.append(arch_report.methods_section(members[0], rows, image))
        else:
            sections.append(arch_report.sweep_section(group, members, rows, image))
    if preset_rows:
        sections.insert(0, arch_report.presets_section(preset_rows, definition.get("method", "none")))
    if family_rows:
        sections.append(arch_report.families_section(family_rows, family_spec, args.families))
        preset = family_spec.get("preset", "small")
        with open(os.path.join(args.results, "method_cycles.json"), "w") as f:
            json.dump({"preset": preset, "rows": family_rows, "provenance": prov}, f, indent=1)

    with open(os.path.join(args.results, "arch_sweep.json"), "w") as f:
        json.dump({"trace": os.path.relpath(trace, ROOT), "rows": rows, "presets": preset_rows,
                   "provenance": prov}, f, indent=1)
    command = "/usr/bin/python3 scripts/arch_sweep.py" + (
        f" --definition {args.definition}" if args.definition else "") + (
        " --only " + " ".join(args.only) if args.only else "")
    if args.families:  # the scored families of make_results.sh, which runs this
        command = "scripts/make_results.sh (which runs " + command + " --families DIR...)"
    intro = arch_report.intro(definition, os.path.relpath(trace, ROOT), rows, preset_rows, family_rows)
    arch_report.write_page(os.path.join(args.out, "architecture.md"), command, intro, sections, prov)
    print(f"arch_sweep: wrote {args.out}/architecture.md, {len(groups)} charts and {args.results}/arch_sweep.json",
          file=sys.stderr)


if __name__ == "__main__":
    main()
