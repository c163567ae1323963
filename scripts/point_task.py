#!/usr/bin/python3
"""One task of a Slurm job array of sweep points (slurm_backend.py submits it):

    point_task.py MANIFEST TASK_ID

runs points [TASK_ID x per_task, (TASK_ID + 1) x per_task) of the manifest,
skipping those already in the cache, prints what failed (into the task's log)
and writes JOB_TASK.status next to the manifest: {"task", "points", "failures"}.
Exit status 1 when a point failed.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from point_jobs import Point, run_point  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: point_task.py MANIFEST TASK_ID")
    manifest, task = sys.argv[1], int(sys.argv[2])
    with open(manifest) as f:
        m = json.load(f)
    per_task = m["per_task"]
    mine = [Point.from_json(p) for p in m["points"][task * per_task:(task + 1) * per_task]]
    failures = []
    for p in mine:
        message = run_point(p)
        print(f"{p.label}: {'failed' if message else 'done'}", flush=True)
        if message:
            print(message, file=sys.stderr, flush=True)
            failures.append(message)
    job = os.environ.get("SLURM_ARRAY_JOB_ID", "local")
    status = os.path.join(os.path.dirname(manifest), f"{job}_{task}.status")
    with open(status + ".part", "w") as f:
        json.dump({"task": task, "points": len(mine), "failures": failures}, f)
    os.replace(status + ".part", status)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
