#!/usr/bin/env python3
"""Verdict table of self-intersection methods on generated scenarios.

Generates each scenario with its default settings (`vbsim gen NAME -o DIR`),
replays every trace of it with each method (`vbsim replay --stats`) and prints
a Markdown table: per method and scenario, self_hit / missed / false_hit of the
secondary rays (every ray that leaves a surface) summed over all cases, then
the camera rays missed in brackets (the tester's, not the method's, errors).

usage: scripts/scenario_verdicts.py [--vbsim build/vbsim] [--rays N] [--seed S]
                                    [--per-case] [--set key=value ...] SCENARIO...
"""
import argparse
import glob
import json
import os
import subprocess
import tempfile

METHODS = ["none", "tmin", "primid", "offset-normal", "offset-direction", "offset-adaptive",
           "offset-errbound", "offset-adaptive+primid", "validity-bit", "sign-only",
           "shading-position"]


def replay(vbsim, trace, method, stats):
    """Secondary rays' self_hit, missed, false_hit and count; camera rays missed."""
    subprocess.run([vbsim, "replay", trace, "-m", method, "--stats", stats, "-q"], check=True)
    with open(stats) as f:
        kinds = json.load(f)["by_kind"]
    sec = [0, 0, 0, 0]
    for kind, k in kinds.items():
        if kind == "primary":
            continue
        v = k["verdicts"]
        for i, x in enumerate((v["self_hit"], v["missed"], v["false_hit"], sum(v.values()))):
            sec[i] += x
    camera = kinds.get("primary", {}).get("verdicts", {}).get("missed", 0)
    return (*sec, camera)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--vbsim", default=os.path.join(os.path.dirname(__file__), "..", "build", "vbsim"))
    ap.add_argument("--rays", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--per-case", action="store_true", help="one column per case instead of per scenario")
    ap.add_argument("--set", action="append", default=[], help="scenario setting key=value (repeatable)")
    ap.add_argument("scenarios", nargs="+")
    a = ap.parse_args()
    columns = []  # (label, [traces])
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.scenarios:
            out = os.path.join(tmp, name)
            subprocess.run([a.vbsim, "gen", name, "--rays", str(a.rays), "--seed", str(a.seed), "-q", "-o", out]
                           + [x for kv in a.set for x in ("--set", kv)],
                           check=True, stdout=subprocess.DEVNULL)
            traces = sorted(glob.glob(os.path.join(out, "*.jsonl")))
            if a.per_case:
                columns += [(os.path.basename(t)[:-6], [t]) for t in traces]
            else:
                columns.append((name, traces))
        rays = {}
        rows = []
        for m in METHODS:
            cells = []
            for label, traces in columns:
                tot = [0, 0, 0, 0, 0]
                for t in traces:
                    for i, x in enumerate(replay(a.vbsim, t, m, os.path.join(tmp, "stats.json"))):
                        tot[i] += x
                rays[label] = tot[3]
                cells.append("{} / {} / {} ({})".format(*tot[:3], tot[4]))
            rows.append("| `{}` | {} |".format(m, " | ".join(cells)))
    print("| method | " + " | ".join("{} ({} secondary rays)".format(l, rays[l]) for l, _ in columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
