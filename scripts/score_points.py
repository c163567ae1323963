#!/usr/bin/python3
"""`vbsim score` over many scenario families as independent points: one
`vbsim score FAMILY --out PART.json` process per family, run on local cores or
as one Slurm job array (point_jobs.py, docs/cluster.md) and cached by content,
then joined with `vbsim score --merge` into the table a single `vbsim score` of
all the families writes (the same rows and counts; only rays_per_s, a timing,
differs).

    /usr/bin/python3 scripts/score_points.py DIR_OR_TRACE... --out FILE
        [--accuracy-md FILE] [--regenerate-with TEXT] [--methods LIST] [--testers LIST]
        [--threads N] [--vbsim build/vbsim] [--work build/score] [--jobs N] [--fresh]
        [--backend slurm [--partition P] [--account A] [--time T] [--max-parallel N]]

A point's key hashes the vbsim binary, the family's files (its traces, its
scenes, and any scene a trace names outside the folder) and the options.
"""
import argparse
import json
import os
import struct
import subprocess
import sys

from point_jobs import Point, add_backend_arguments, check_backend_arguments, content_key, file_digest, run_points

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TRACE_EXTENSIONS = (".jsonl", ".vbt")


def trace_header(path):
    """The header object of a text or binary trace."""
    with open(path, "rb") as f:
        start = f.read(16)
        if start[:8] == b"VBSIMTRB":
            (length,) = struct.unpack("<I", start[12:16])
            return json.loads(f.read(length))
        f.seek(0)
        return json.loads(f.readline())


def family_files(path):
    """Every file a family's score depends on: its traces and the scenes they name."""
    if os.path.isdir(path):
        traces = sorted(os.path.join(path, n) for n in os.listdir(path) if n.endswith(TRACE_EXTENSIONS))
    else:
        traces = [path]
    if not traces:
        sys.exit(f"score_points: {path}: no trace files (.jsonl, .vbt)")
    files = list(traces)
    for t in traces:
        scene = trace_header(t)["scene"]
        files.append(scene if os.path.isabs(scene) else os.path.normpath(os.path.join(os.path.dirname(t), scene)))
    return sorted(set(files))


def family_point(vbsim, path, options, cache):
    files = family_files(path)
    digests = {os.path.relpath(f, os.path.dirname(os.path.abspath(path))): file_digest(f) for f in files}
    key = content_key(vbsim=file_digest(vbsim), family=os.path.basename(os.path.normpath(path)), files=digests,
                      options=options)
    result = os.path.join(cache, key + ".score.json")
    return Point(path, [[vbsim, "score", path, *options, "-q", "--out", result + ".part"]], result)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("paths", nargs="+", help="scenario folders (families) or trace files")
    ap.add_argument("--out", required=True, help="the merged score table (JSON)")
    ap.add_argument("--accuracy-md", help="the merged table as markdown")
    ap.add_argument("--regenerate-with", help="the command the markdown names for regenerating it")
    ap.add_argument("--methods", help="as vbsim score --methods [its default list]")
    ap.add_argument("--testers", help="as vbsim score --testers [its default]")
    ap.add_argument("--threads", type=int, default=1, help="threads per vbsim score process (and Slurm task)")
    ap.add_argument("--mode", choices=["functional", "cycle"], help="as vbsim score --mode [functional]")
    ap.add_argument("--preset", help="as vbsim score --preset (cycle mode)")
    ap.add_argument("--cycle-testers", help="as vbsim score --cycle-testers (cycle mode)")
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "score"), help="cached per-family tables")
    add_backend_arguments(ap)
    args = ap.parse_args()
    check_backend_arguments(ap, args)
    if args.threads < 1:
        ap.error("--threads must be >= 1")
    args.cpus_per_task = args.threads
    if not os.path.exists(args.vbsim):
        sys.exit(f"score_points: no vbsim binary at {args.vbsim} (build with scripts/setup.sh)")
    vbsim = os.path.abspath(args.vbsim)
    options = ["--threads", str(args.threads)]
    if args.methods:
        options += ["--methods", args.methods]
    if args.testers:
        options += ["--testers", args.testers]
    for flag, value in (("--mode", args.mode), ("--preset", args.preset), ("--cycle-testers", args.cycle_testers)):
        if value:
            options += [flag, value]
    points = [family_point(vbsim, p, options, os.path.join(args.work, "points")) for p in args.paths]
    run_points(points, args, args.work, "score_points")
    merge = [vbsim, "score", "--merge", *[p.result for p in points], "--out", args.out, "-q"]
    if args.accuracy_md:
        merge += ["--accuracy-md", args.accuracy_md]
    if args.regenerate_with:
        merge += ["--regenerate-with", args.regenerate_with]
    proc = subprocess.run(merge, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"score_points: merging failed ({proc.returncode}): {' '.join(merge)}\n{proc.stderr}")
    print(f"score_points: {len(points)} families -> {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
