#!/usr/bin/python3
"""Regenerates traces/bunny/paths.expected.json: the verdict and avoidance
counts of the bundled default trace under each listed method, as the system
test `default trace statistics match the committed expectations` checks them.

Run after a deliberate change of behaviour, and say why in the commit:
    /usr/bin/python3 scripts/update_expected_stats.py [path/to/vbsim]
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TRACE = os.path.join(ROOT, "traces", "bunny", "paths.jsonl")
OUT = os.path.join(ROOT, "traces", "bunny", "paths.expected.json")
# (label, extra command-line arguments)
RUNS = [
    ("none", ["--method", "none"]),
    ("tmin", ["--method", "tmin"]),
    ("primid", ["--method", "primid"]),
    ("offset-normal", ["--method", "offset-normal"]),
    ("offset-direction", ["--method", "offset-direction"]),
    ("offset-adaptive", ["--method", "offset-adaptive"]),
    ("offset-adaptive+primid", ["--method", "offset-adaptive+primid"]),
    ("offset-errbound", ["--method", "offset-errbound"]),
    ("validity-bit", ["--method", "validity-bit"]),
    ("validity-bit vote", ["--method", "validity-bit", "--vb-policy", "vote"]),
    ("validity-bit fixed 1e-4", ["--method", "validity-bit", "--vb-eps-mode", "fixed", "--vb-eps", "1e-4"]),
    ("sign-only", ["--method", "sign-only"]),
    ("shading-position", ["--method", "shading-position"]),
    ("reverse-shadow", ["--method", "reverse-shadow"]),
    ("none moller-trumbore", ["--method", "none", "--tester", "moller-trumbore"]),
    ("none barycentric", ["--method", "none", "--hitpoint", "barycentric"]),
    ("none ray", ["--method", "none", "--hitpoint", "ray"]),
]


def summary(stats):
    """The parts of a stats file the system test compares."""
    return {
        "args": None,
        "rays": stats["rays"],
        "verdicts": stats["verdicts"],
        "by_kind": {k: v["verdicts"] for k, v in stats["by_kind"].items()},
        "avoidance": {k: stats["avoidance"][k] for k in ("candidates", "suspects", "rejected")},
        "emission_fallbacks": stats["emission_fallbacks"],
    }


def main():
    vbsim = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "vbsim")
    result = {"trace": "paths.jsonl", "runs": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for label, args in RUNS:
            stats_path = os.path.join(tmp, "stats.json")
            subprocess.run([vbsim, "replay", TRACE, "--quiet", "--stats", stats_path] + args, check=True)
            with open(stats_path) as f:
                entry = summary(json.load(f))
            entry["args"] = args
            result["runs"][label] = entry
    with open(OUT, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
