"""Independent points of a sweep, run on local cores or as one Slurm job array
(used by arch_sweep.py, sweep.py and score_points.py).

A point is a few commands run one after another and the result file the last
one writes. Commands write the result under its temporary name (`part`), and
the runner renames it only when every command succeeded, so a result file in
the cache is always a finished point. Results live in a content-hash cache:
the caller names each point's file by a key that hashes everything the result
depends on (the vbsim binary's bytes, the inputs' bytes, the options), so a
rerun, or a resubmission to a cluster, skips every point already finished.

A command is a list of arguments; an argument {"glob": PATTERN} becomes the
sorted files matching PATTERN when the command runs (traces that an earlier
command of the point generated).

    add_backend_arguments(parser)               --backend, --jobs, Slurm options
    results = run_points(points, args, work, label)
"""
import glob
import hashlib
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

from progress_line import ProgressLine


class Point:
    """Commands and the result file they make; `label` names the point in messages."""

    def __init__(self, label, commands, result):
        self.label, self.commands, self.result = label, commands, result

    @property
    def part(self):
        return self.result + ".part"

    def to_json(self):
        return {"label": self.label, "commands": self.commands, "result": self.result}

    @staticmethod
    def from_json(j):
        return Point(j["label"], j["commands"], j["result"])


def file_digest(path, _cache={}):
    """SHA-256 of a file's bytes (a trace, a scene, the vbsim binary), once per path and run."""
    if path not in _cache:
        h = hashlib.sha256()
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
        _cache[path] = h.hexdigest()
    return _cache[path]


def content_key(**parts):
    """A cache key: the first 20 hex digits of SHA-256 over the parts as sorted JSON."""
    return hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()[:20]


def write_json_once(path, data, **dump_options):
    """Writes `data` as JSON to `path` unless it is there (a point's configuration,
    named by its content key): under a temporary name, renamed when complete."""
    if os.path.exists(path):
        return
    with open(path + ".part", "w") as f:
        json.dump(data, f, **dump_options)
    os.replace(path + ".part", path)


def expand(command):
    """The command's arguments with every {"glob": PATTERN} replaced by its matches."""
    out = []
    for arg in command:
        if isinstance(arg, dict):
            matches = sorted(glob.glob(arg["glob"]))
            if not matches:
                raise RuntimeError(f"no file matches {arg['glob']}")
            out += matches
        else:
            out.append(str(arg))
    return out


def run_point(point):
    """Runs a point's commands; None when it finished, else a message saying what failed."""
    if os.path.exists(point.result):
        return None
    os.makedirs(os.path.dirname(point.result) or ".", exist_ok=True)
    for command in point.commands:
        try:
            argv = expand(command)
        except RuntimeError as e:
            return f"point {point.label}: {e}"
        proc = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            tail = "\n".join(proc.stderr.strip().splitlines()[-20:])
            return f"point {point.label}: command failed ({proc.returncode}): {' '.join(argv)}\n{tail}"
    if not os.path.exists(point.part):
        return f"point {point.label}: its commands wrote no {point.part}"
    os.replace(point.part, point.result)  # only a finished point enters the cache
    return None


def add_backend_arguments(parser):
    """--backend local|slurm and what each needs."""
    g = parser.add_argument_group("where the points run")
    g.add_argument("--backend", choices=("local", "slurm"), default="local",
                   help="local: parallel processes on this machine; slurm: one sbatch job array (docs/cluster.md)")
    g.add_argument("--jobs", type=int, default=os.cpu_count() or 2, help="local: parallel processes")
    g.add_argument("--partition", help="slurm: sbatch --partition")
    g.add_argument("--account", help="slurm: sbatch --account")
    g.add_argument("--time", help="slurm: sbatch --time, per array task (e.g. 0:30:00)")
    g.add_argument("--max-parallel", type=int, help="slurm: array tasks running at once (--array=...%%N)")
    g.add_argument("--points-per-task", type=int,
                   help="slurm: points each array task runs [enough to keep the array within 1000 tasks]")
    g.add_argument("--fresh", action="store_true", help="rerun points already in the cache")


def check_backend_arguments(parser, args):
    if args.jobs < 1:
        parser.error("--jobs must be >= 1")
    if args.backend == "local":
        given = [o for o in ("partition", "account", "time", "max_parallel", "points_per_task")
                 if getattr(args, o) is not None]
        if given:
            parser.error(f"--{given[0].replace('_', '-')} needs --backend slurm")
    for o in ("max_parallel", "points_per_task"):
        if getattr(args, o) is not None and getattr(args, o) < 1:
            parser.error(f"--{o.replace('_', '-')} must be >= 1")


def run_local(points, jobs, label):
    """Runs the points on `jobs` processes; the failure messages."""
    progress = ProgressLine(label, len(points), "points")
    failures = []

    def one(p):
        message = run_point(p)
        progress.add(1)
        return message

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        failures = [m for m in pool.map(one, points) if m]
    progress.finish()
    return failures


def run_points(points, args, work, label):
    """Runs every point not yet in the cache (all with --fresh) and returns their
    results (parsed JSON) in order; exits with every failure reported when a point failed."""
    if args.fresh:
        for p in points:
            if os.path.exists(p.result):
                os.remove(p.result)
    todo = [p for p in points if not os.path.exists(p.result)]
    print(f"{label}: {len(points)} points, {len(points) - len(todo)} already in the cache, "
          f"{len(todo)} to run ({args.backend})", file=sys.stderr)
    started = time.time()
    if args.backend == "slurm":
        import slurm_backend
        failures = slurm_backend.run_array(todo, args, os.path.join(work, "slurm"), label)
    else:
        failures = run_local(todo, args.jobs, label)
    if failures:
        sys.exit(f"{label}: {len(failures)} failure(s):\n" + "\n".join(failures))
    if todo:
        print(f"{label}: {len(todo)} points in {time.time() - started:.1f} s", file=sys.stderr)
    results = []
    for p in points:
        with open(p.result) as f:
            results.append(json.load(f))
    return results
