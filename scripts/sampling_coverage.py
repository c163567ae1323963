#!/usr/bin/python3
"""How often a sampled run's confidence interval holds the full run's cycles.

For each workload (a trace and a preset), runs the full cycle-level replay
once, then the sampled replay (`vbsim replay --mode cycle --sample`,
docs/sampling.md) once for every offset 0 .. N-1 of the measured unit inside
its interval (`--sample-offset`: each offset is a different systematic sample
of the same trace, the sampling's "seed"), and counts the runs whose interval
holds the full run's figure. Prints and writes (as markdown) per workload:
the runs, the coverage with its own 95% Wilson interval, the errors (mean,
largest), the intervals' mean relative half-width, and the wall times of the
full and the sampled runs (medians).

  /usr/bin/python3 scripts/sampling_coverage.py --vbsim build/vbsim \\
      --workload p1m.vbt:small --workload p1m.vbt:large --interval 20 --offsets 20 \\
      --out coverage.md [-- EXTRA SAMPLE OPTIONS]

Outputs are written to a temporary name and renamed when complete.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time


def run_replay(vbsim, trace, preset, method, extra, stats):
    """One `vbsim replay --mode cycle` (full, or sampled with `extra`); its wall time and hw section."""
    cmd = [vbsim, "replay", trace, "--mode", "cycle", "--preset", preset, "-m", method, "-q", "--stats", stats] + extra
    t = time.monotonic()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - t
    if proc.returncode != 0:
        sys.exit(f"sampling_coverage: {' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.strip()}")
    with open(stats) as f:
        return wall, json.load(f)["hw"]


def wilson(k, n, z=1.959963984540054):
    """The 95% Wilson score interval of k successes in n trials."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def measure(vbsim, trace, preset, method, interval, offsets, extra, tmp):
    full_wall, full = run_replay(vbsim, trace, preset, method, [], os.path.join(tmp, "full.json"))
    truth = full["cycles"]
    runs = []
    for k in range(offsets):
        opts = ["--sample", "--sample-interval", str(interval), "--sample-offset", str(k % interval)] + extra
        wall, hw = run_replay(vbsim, trace, preset, method, opts, os.path.join(tmp, f"s{k}.json"))
        low, high = hw["sampling"]["intervals"]["cycles"]
        runs.append({"offset": k % interval, "estimate": hw["cycles"], "low": low, "high": high,
                     "error": (hw["cycles"] - truth) / truth, "half": (high - low) / 2 / hw["cycles"],
                     "covers": low <= truth <= high, "wall_s": wall})
    covered = sum(r["covers"] for r in runs)
    lo, hi = wilson(covered, len(runs))
    return {"trace": trace, "preset": preset, "full_cycles": truth, "full_wall_s": full_wall, "runs": runs,
            "covered": covered, "coverage": covered / len(runs), "coverage_interval": [lo, hi],
            "mean_abs_error": statistics.mean(abs(r["error"]) for r in runs),
            "max_abs_error": max(abs(r["error"]) for r in runs),
            "mean_half_width": statistics.mean(r["half"] for r in runs),
            "sampled_wall_s": statistics.median(r["wall_s"] for r in runs)}


def page(results, args, extra):
    L = ["| trace | preset | runs | covered | coverage [95% interval] | mean abs error | largest abs error | "
         "mean half-width | full wall s | sampled wall s (median) |",
         "|---|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for r in results:
        lo, hi = r["coverage_interval"]
        name = os.path.join(os.path.basename(os.path.dirname(os.path.abspath(r["trace"]))), os.path.basename(r["trace"]))
        L.append(f"| `{name}` | {r['preset']} | {len(r['runs'])} | {r['covered']} | "
                 f"{r['coverage']:.2f} [{lo:.2f}, {hi:.2f}] | {100 * r['mean_abs_error']:.2f}% | "
                 f"{100 * r['max_abs_error']:.2f}% | {100 * r['mean_half_width']:.2f}% | {r['full_wall_s']:.2f} | "
                 f"{r['sampled_wall_s']:.2f} |")
    cmd = " ".join(["scripts/sampling_coverage.py"] + sys.argv[1:])
    return "\n".join([f"<!-- {cmd} -->", ""] + L) + "\n"


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--vbsim", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "vbsim"))
    p.add_argument("--workload", action="append", required=True, help="TRACE:PRESET (repeatable)")
    p.add_argument("--method", default="validity-bit")
    p.add_argument("--interval", type=int, default=20, help="--sample-interval of every sampled run [20]")
    p.add_argument("--offsets", type=int, default=20, help="sampled runs a workload, offsets 0 .. N-1 [20]")
    p.add_argument("--out", help="markdown table (and OUT.json with every run)")
    args = p.parse_args(argv)
    if args.offsets < 1 or args.interval < 1:
        sys.exit("sampling_coverage: --offsets and --interval must be at least 1")
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for w in args.workload:
            trace, _, preset = w.rpartition(":")
            if not trace or not os.path.exists(trace):
                sys.exit(f"sampling_coverage: --workload '{w}': expected TRACE:PRESET with an existing trace")
            r = measure(args.vbsim, trace, preset, args.method, args.interval, args.offsets, extra, tmp)
            results.append(r)
            lo, hi = r["coverage_interval"]
            print(f"{trace} {preset}: {r['covered']} of {len(r['runs'])} intervals hold the full run's "
                  f"{r['full_cycles']} cycles (coverage {r['coverage']:.2f}, [{lo:.2f}, {hi:.2f}]); mean |error| "
                  f"{100 * r['mean_abs_error']:.2f}%, largest {100 * r['max_abs_error']:.2f}%, mean half-width "
                  f"{100 * r['mean_half_width']:.2f}%; wall {r['full_wall_s']:.2f} s full, "
                  f"{r['sampled_wall_s']:.2f} s sampled (median)", flush=True)
    if args.out:
        for path, text in ((args.out, page(results, args, extra)),
                           (args.out + ".json", json.dumps(results, indent=1) + "\n")):
            with open(path + ".partial", "w") as f:
                f.write(text)
            os.replace(path + ".partial", path)


if __name__ == "__main__":
    main()
