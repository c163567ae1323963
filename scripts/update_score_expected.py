#!/usr/bin/python3
"""Regenerates traces/ci/score.expected.json: the exact counts of `vbsim score`
on small fixed-seed scenario cases and the bundled trace, as the system test
`score of the CI scenarios matches the committed counts` checks them.

Run after a deliberate change of behaviour (or to add scenarios or methods to
the CI subset), and say why in the commit:
    /usr/bin/python3 scripts/update_score_expected.py [path/to/vbsim]
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "traces", "ci", "score.expected.json")
# (family directory name, `vbsim gen` arguments before -o; {source} stands for the
# source tree, which the test replaces with its own)
GEN = [
    ("paths", "paths --rays 25 --seed 11"),
    ("paths-wuson", "paths --rays 12 --seed 11 --set scene={source}/traces/wuson/WusonOBJ.obj"),
    ("random-triangles-rtg", "random-triangles --rays 12 --seed 11"),
    ("random-triangles-pbrt", "random-triangles --rays 12 --seed 11 --set protocol=pbrt"),
    ("random-triangles-pbrt-v4", "random-triangles --rays 12 --set protocol=pbrt-v4 --set first=11"),
    ("grazing", "grazing --rays 12 --seed 11"),
    ("shared-edges", "shared-edges --rays 12 --seed 11"),
    ("crevice", "crevice --rays 12 --seed 11"),
    ("corner", "corner --rays 12 --seed 11"),
    ("layers", "layers --rays 12 --seed 11"),
    ("coplanar", "coplanar --rays 12 --seed 11"),
    ("far-instance", "far-instance --rays 12 --seed 11"),
    ("refraction", "refraction --rays 12 --seed 11"),
    ("terminator", "terminator --rays 12 --seed 11"),
]
BUNDLED = "traces/bunny"
METHODS = ",".join([
    "none", "tmin", "primid", "offset-normal", "offset-adaptive", "offset-errbound", "validity-bit",
    "validity-bit:vb-eps-mode=fixed:vb-eps=1e-4", "validity-bit:vb-policy=vote", "sign-only",
    "shading-position+offset-adaptive", "reverse-shadow",
])
TESTERS = "three-half-plane,moller-trumbore,pbrt-watertight"


def main():
    vbsim = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "vbsim")
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for family, args in GEN:
            out = os.path.join(tmp, family)
            subprocess.run([vbsim, "gen"] + args.replace("{source}", ROOT).split() + ["-q", "-o", out], check=True, stdout=subprocess.DEVNULL)
            paths.append(out)
        paths.append(os.path.join(ROOT, BUNDLED))
        score_path = os.path.join(tmp, "score.json")
        subprocess.run([vbsim, "score"] + paths + ["-q", "--methods", METHODS, "--testers", TESTERS,
                                                   "--out", score_path], check=True)
        with open(score_path) as f:
            score = json.load(f)
    rows = [{
        "family": r["family"], "method": r["method"], "tester": r["tester"], "kind": r["kind"],
        "counts": r["counts"], "suspects": r["avoidance"]["suspects"], "rejected": r["avoidance"]["rejected"],
    } for r in score["rows"]]
    result = {
        "gen": [{"family": family, "args": args} for family, args in GEN],
        "bundled": BUNDLED,
        "methods": METHODS,
        "testers": TESTERS,
        "rows": rows,
    }
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    # One row per line: small, and a change of behaviour shows as changed rows.
    head = json.dumps({k: v for k, v in result.items() if k != "rows"}, indent=1)[:-2]
    with open(OUT, "w") as f:
        f.write(head + ',\n "rows": [\n')
        f.write(",\n".join("  " + json.dumps(r, separators=(",", ":")) for r in rows))
        f.write("\n ]\n}\n")
    print(f"wrote {OUT} ({len(rows)} rows)")


if __name__ == "__main__":
    main()
