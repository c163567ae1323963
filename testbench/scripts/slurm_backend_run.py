#!/usr/bin/python3
"""The Slurm backend end to end on a real one-node cluster on localhost
(local_slurm.py): arch_sweep.py, sweep.py and score_points.py each run a small
sweep as one sbatch job array and must give the local backend's results; a
resubmission finds every point in the cache; a failing point is reported with
its task id and log.

    /usr/bin/python3 slurm_backend_run.py PATH_TO_VBSIM

Needs root (slurmd, munged). Run as another user it exits 77, which ctest
counts as skipped (SKIP_RETURN_CODE); as root, a cluster that does not start
is a failure saying which daemon failed and why.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import types
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from arch_sweep_run import DEFINITION as ARCH_DEFINITION  # noqa: E402
from local_slurm import ClusterError, LocalSlurm  # noqa: E402
from point_jobs import Point  # noqa: E402
import slurm_backend  # noqa: E402

SKIP = 77
VBSIM = None
SWEEP_DEFINITION = [{
    "name": "tiny", "scenario": "crevice", "rays": 6, "seed": 1, "title": "Crevice angle, tiny",
    "about": "two crevice angles", "key": "angles", "set": {}, "values": [5, 20], "xlog": False, "hard": "low",
    "xlabel": "angle", "unit": "deg",
    "methods": [{"label": "none", "spec": "none"}, {"label": "validity-bit", "spec": "validity-bit"}]}]


def load(path):
    with open(path) as f:
        return json.load(f)


class SlurmBackendTest(unittest.TestCase):
    cluster = None

    @classmethod
    def setUpClass(cls):
        try:
            cls.cluster = LocalSlurm(cpus=2).__enter__()
        except ClusterError as e:
            raise RuntimeError(f"could not start the test's Slurm cluster: {e}") from None
        cls.env = {**cls.cluster.env, "VBSIM_SLURM_POLL_SECONDS": "0.3"}
        cls.tmp = tempfile.TemporaryDirectory(prefix="vbsim_slurm_run_")
        cls.d = cls.tmp.name

    @classmethod
    def tearDownClass(cls):
        if cls.cluster:
            cls.cluster.stop()
        cls.tmp.cleanup()

    def run_script(self, script, *args):
        cmd = [sys.executable, os.path.join(ROOT, "scripts", script), *args]
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=self.env)
        self.assertEqual(proc.returncode, 0, f"{' '.join(cmd)}\n{proc.stderr}")
        return proc.stderr

    def slurm(self):
        return ["--backend", "slurm", "--partition", "test", "--time", "10", "--max-parallel", "2"]

    def test_arch_sweep_on_slurm_equals_local_and_resubmits_nothing(self):
        definition = os.path.join(self.d, "arch.json")
        with open(definition, "w") as f:
            json.dump(ARCH_DEFINITION, f)
        def arch_sweep(base, *extra):
            return self.run_script("arch_sweep.py", "--vbsim", VBSIM, "--definition", definition, "--work",
                                   os.path.join(base, "work"), "--out", os.path.join(base, "out"), "--results",
                                   os.path.join(base, "results"), *extra)

        outputs = {}
        for backend in ("local", "slurm"):
            base = os.path.join(self.d, "arch-" + backend)
            err = arch_sweep(base, *(self.slurm() if backend == "slurm" else ["--jobs", "2"]))
            if backend == "slurm":
                self.assertIn("submitted Slurm job array", err)
            outputs[backend] = [load(os.path.join(base, "results", name))
                                for name in ("arch_sweep.json", "method_cycles.json")]
        for local, slurm in zip(outputs["local"], outputs["slurm"]):
            self.assertGreater(len(local["rows"]), 1)
            self.assertEqual(local["rows"], slurm["rows"])
        # A resubmission finds every point in the cache and submits nothing.
        err = arch_sweep(os.path.join(self.d, "arch-slurm"), *self.slurm())
        self.assertIn("0 to run", err)
        self.assertNotIn("submitted", err)

    def test_stability_sweep_on_slurm_equals_local(self):
        definition = os.path.join(self.d, "sweep.json")
        with open(definition, "w") as f:
            json.dump(SWEEP_DEFINITION, f)
        tables = {}
        for backend in ("local", "slurm"):
            base = os.path.join(self.d, "sweep-" + backend)
            self.run_script("sweep.py", "--vbsim", VBSIM, "--definition", definition, "--work",
                            os.path.join(base, "work"), "--out", os.path.join(base, "out"),
                            *(self.slurm() if backend == "slurm" else []))
            with open(os.path.join(base, "out", "sweeps.csv")) as f:
                self.assertTrue(f.readline().startswith("# vbsim-provenance "))
                tables[backend] = list(csv.DictReader(f))
        self.assertEqual(len(tables["local"]), 4)  # 2 angles x 2 methods
        self.assertEqual(tables["local"], tables["slurm"])

    def test_score_points_on_slurm_equals_one_score_run(self):
        families = []
        for scenario in ("corner", "coplanar"):
            families.append(os.path.join(self.d, "families", scenario))
            subprocess.run([VBSIM, "gen", scenario, "--rays", "6", "-q", "-o", families[-1]], check=True)
        methods = ["--methods", "none,validity-bit:vb-policy=vote", "--testers", "three-half-plane"]
        one = os.path.join(self.d, "one.json")
        subprocess.run([VBSIM, "score", *families, *methods, "-q", "--out", one], check=True)
        merged = os.path.join(self.d, "merged.json")
        self.run_script("score_points.py", *families, *methods, "--vbsim", VBSIM, "--work",
                        os.path.join(self.d, "score-work"), "--out", merged, *self.slurm())
        strip = lambda t: [{k: v for k, v in r.items() if k != "rays_per_s"} for r in t["rows"]]  # noqa: E731
        a, b = load(one), load(merged)
        self.assertEqual(a["families"], b["families"])
        self.assertEqual(strip(a), strip(b))

    def test_suite_cells_on_slurm_equal_local(self):
        tables = {}
        for backend in ("local", "slurm"):
            out = os.path.join(self.d, "suite-" + backend)
            err = self.run_script("suite.py", "--small", "--scenes", "layers", "--types", "shadow,glass", "--vbsim",
                                  VBSIM, "--out", out, *(self.slurm() if backend == "slurm" else []))
            if backend == "slurm":
                self.assertIn("submitted Slurm job array", err)
            with open(os.path.join(out, "results", "suite.csv")) as f:
                self.assertTrue(f.readline().startswith("# vbsim-provenance "))
                tables[backend] = list(csv.DictReader(f))
        self.assertGreater(len(tables["local"]), 20)  # two ray types, every method
        self.assertEqual(tables["local"], tables["slurm"])  # errors, cycles, energy and area alike

    def test_a_failed_task_is_reported_with_its_id_and_log(self):
        work = os.path.join(self.d, "failing")
        good = Point("good", [["/bin/sh", "-c", f"echo ok > {work}/good.json.part"]], f"{work}/good.json")
        bad = Point("bad", [["/bin/sh", "-c", "echo broken >&2; exit 3"]], f"{work}/bad.json")
        args = types.SimpleNamespace(partition="test", account=None, time="5", max_parallel=None, points_per_task=1)
        os.makedirs(work)
        old = os.environ.get("SLURM_CONF")
        os.environ["SLURM_CONF"] = self.env["SLURM_CONF"]
        try:
            failures = slurm_backend.run_array([good, bad], args, os.path.join(work, "slurm"), "failing")
        finally:
            if old is None:
                del os.environ["SLURM_CONF"]
            else:
                os.environ["SLURM_CONF"] = old
        self.assertTrue(os.path.exists(good.result))
        self.assertEqual(len(failures), 1, failures)
        self.assertRegex(failures[0], r"^task \d+_1 failed 1 of 1 points; log \S+_1\.out")
        self.assertIn("command failed (3)", failures[0])
        log = failures[0].split("; log ")[1].split("\n")[0]
        with open(log) as f:
            self.assertIn("broken", f.read())


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: slurm_backend_run.py PATH_TO_VBSIM")
    VBSIM = os.path.abspath(sys.argv.pop(1))
    if os.geteuid() != 0:
        print("slurm_backend_run: skipped: starting slurmd and munged needs root", file=sys.stderr)
        sys.exit(SKIP)
    unittest.main()
