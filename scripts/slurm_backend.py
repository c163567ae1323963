"""The Slurm backend of point_jobs.py: the points go to one `sbatch` job array.

Each array task runs its share of the points (point_task.py: points
[task x per_task, (task + 1) x per_task) of a manifest written next to the logs),
skipping any whose result is already in the cache, and writes its results into
the same content-hash cache as a local run, so compute nodes need the work
folder on a shared file system. The submitting process polls `squeue` until the
array has left the queue, showing progress by the results that have appeared,
then reports every failed task with its id and log (WORK/slurm/JOB_TASK.out).
A resubmission runs only the points still missing.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import time

from progress_line import ProgressLine

MAX_ARRAY_TASKS = 1000  # Slurm's default MaxArraySize is 1001
POLL_SECONDS = float(os.environ.get("VBSIM_SLURM_POLL_SECONDS", "2"))
HERE = os.path.dirname(os.path.abspath(__file__))


def sbatch_command(args, tasks, slurm_dir, script, label):
    """The sbatch argument list for an array of `tasks` tasks."""
    array = f"0-{tasks - 1}" + (f"%{args.max_parallel}" if args.max_parallel else "")
    cmd = ["sbatch", "--parsable", f"--job-name=vbsim-{label}", f"--array={array}", "--ntasks=1",
           f"--output={os.path.join(slurm_dir, '%A_%a.out')}", f"--chdir={os.getcwd()}"]
    if getattr(args, "cpus_per_task", None):
        cmd.append(f"--cpus-per-task={args.cpus_per_task}")
    for option in ("partition", "account", "time"):
        if getattr(args, option):
            cmd.append(f"--{option}={getattr(args, option)}")
    return cmd + [script]


def write_job_files(points, per_task, slurm_dir, label):
    """The manifest the tasks read and the batch script; their paths."""
    os.makedirs(slurm_dir, exist_ok=True)
    stem = os.path.join(slurm_dir, f"{label}-{time.strftime('%Y%m%d-%H%M%S')}-{os.getpid()}")
    manifest = stem + ".json"
    with open(manifest, "w") as f:
        json.dump({"per_task": per_task, "points": [p.to_json() for p in points]}, f, indent=1)
    script = stem + ".sh"
    with open(script, "w") as f:
        f.write("#!/bin/sh\n# vbsim sweep points: array task $SLURM_ARRAY_TASK_ID runs its share of the manifest.\n"
                f"exec {sys.executable} {os.path.join(HERE, 'point_task.py')} {manifest} \"$SLURM_ARRAY_TASK_ID\"\n")
    os.chmod(script, 0o755)
    return manifest, script


def queued(job):
    """True while some task of the array is pending or running."""
    proc = subprocess.run(["squeue", "-h", "-j", str(job), "-o", "%i"], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        if "Invalid job id" in proc.stderr:  # already purged from the controller: finished
            return False
        raise RuntimeError(f"squeue failed ({proc.returncode}): {proc.stderr.strip()}")
    return bool(proc.stdout.strip())


def task_failures(job, tasks, slurm_dir):
    """Messages for every task that failed or left no status, with its log path."""
    out = []
    for task in range(tasks):
        log = os.path.join(slurm_dir, f"{job}_{task}.out")
        status_path = os.path.join(slurm_dir, f"{job}_{task}.status")
        if not os.path.exists(status_path):
            out.append(f"task {job}_{task} ended without a status (killed: time limit, memory, node failure, "
                       f"or never started); log {log}")
            continue
        with open(status_path) as f:
            status = json.load(f)
        if status["failures"]:
            out.append(f"task {job}_{task} failed {len(status['failures'])} of {status['points']} points; "
                       f"log {log}\n" + "\n".join(status["failures"]))
    return out


def run_array(points, args, slurm_dir, label):
    """Submits `points` as one array, waits for it, returns failure messages."""
    if not points:
        return []
    for tool in ("sbatch", "squeue"):
        if not shutil.which(tool):
            sys.exit(f"{label}: --backend slurm needs Slurm's `{tool}` on PATH (Debian: slurm-client)")
    per_task = args.points_per_task or math.ceil(len(points) / MAX_ARRAY_TASKS)
    tasks = math.ceil(len(points) / per_task)
    manifest, script = write_job_files(points, per_task, slurm_dir, label)
    cmd = sbatch_command(args, tasks, slurm_dir, script, label)
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"{label}: sbatch failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr.strip()}")
    job = proc.stdout.strip().split(";")[0]
    print(f"{label}: submitted Slurm job array {job}: {tasks} tasks of up to {per_task} points; "
          f"logs {slurm_dir}/{job}_TASK.out", file=sys.stderr)
    progress = ProgressLine(f"{label}: slurm job {job}", len(points), "points")
    try:
        while queued(job):
            progress.update(sum(os.path.exists(p.result) for p in points))
            time.sleep(POLL_SECONDS)
    except KeyboardInterrupt:
        progress.finish()
        sys.exit(f"\n{label}: stopped waiting; job {job} keeps running (cancel it with `scancel {job}`); "
                 "a rerun picks up its results")
    progress.finish()
    failures = task_failures(job, tasks, slurm_dir)
    missing = [p for p in points if not os.path.exists(p.result)]
    if missing and not failures:
        failures.append(f"job {job}: {len(missing)} points have no result although no task failed "
                        f"(first: {missing[0].label}); logs {slurm_dir}/{job}_*.out")
    return failures
