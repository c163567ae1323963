#!/usr/bin/python3
"""The sweep points' runner and its Slurm job files on hand-made points (no
cluster: slurm_backend_run.py runs a real one), the progress line, and the
provenance stamps of the result scripts."""
import json
import os
import struct
import sys
import tempfile
import types
import unittest
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from point_jobs import Point, content_key, expand, run_local, run_point  # noqa: E402
from progress_line import clock_text, progress_text  # noqa: E402
import provenance  # noqa: E402
import slurm_backend  # noqa: E402


def read(path, mode="r"):
    with open(path, mode) as f:
        return f.read()


def writer(path, text):
    return ["/bin/sh", "-c", f"printf '{text}' > {path}"]


class RunPointTest(unittest.TestCase):
    def test_a_point_enters_the_cache_only_when_every_command_succeeded(self):
        with tempfile.TemporaryDirectory() as d:
            ok = Point("ok", [writer(f"{d}/a.json.part", "1")], f"{d}/a.json")
            self.assertIsNone(run_point(ok))
            self.assertEqual(read(ok.result), "1")
            self.assertFalse(os.path.exists(ok.part))
            failing = Point("bad", [writer(f"{d}/b.json.part", "2"), ["/bin/sh", "-c", "echo oops >&2; exit 4"]],
                            f"{d}/b.json")
            message = run_point(failing)
            self.assertIn("point bad: command failed (4)", message)
            self.assertIn("oops", message)
            self.assertFalse(os.path.exists(failing.result))
            silent = Point("silent", [["/bin/true"]], f"{d}/c.json")
            self.assertIn("wrote no", run_point(silent))

    def test_a_finished_point_is_not_run_again(self):
        with tempfile.TemporaryDirectory() as d:
            with open(f"{d}/a.json", "w") as f:
                f.write("old")
            self.assertIsNone(run_point(Point("a", [["/bin/false"]], f"{d}/a.json")))
            self.assertEqual(read(f"{d}/a.json"), "old")

    def test_glob_arguments_expand_when_the_command_runs(self):
        with tempfile.TemporaryDirectory() as d:
            for name in ("b.jsonl", "a.jsonl", "c.ply"):
                open(os.path.join(d, name), "w").close()
            self.assertEqual(expand(["x", {"glob": f"{d}/*.jsonl"}, 3]), ["x", f"{d}/a.jsonl", f"{d}/b.jsonl", "3"])
            with self.assertRaises(RuntimeError):
                expand([{"glob": f"{d}/*.vbt"}])

    def test_local_runs_report_every_failure_and_keep_the_successes(self):
        with tempfile.TemporaryDirectory() as d:
            points = [Point(str(i), [writer(f"{d}/{i}.part", str(i))] if i % 2 else [["/bin/false"]],
                            f"{d}/{i}") for i in range(6)]
            failures = run_local(points, 3, "t")
            self.assertEqual(sorted(f.split(":")[0] for f in failures), ["point 0", "point 2", "point 4"])
            self.assertEqual(sorted(os.listdir(d)), ["1", "3", "5"])

    def test_keys_depend_on_every_part(self):
        a = content_key(vbsim="x", options=["--a"])
        self.assertEqual(a, content_key(options=["--a"], vbsim="x"))
        self.assertNotEqual(a, content_key(vbsim="y", options=["--a"]))
        self.assertEqual(len(a), 20)


class SlurmFilesTest(unittest.TestCase):
    def test_sbatch_passes_the_options_through(self):
        args = types.SimpleNamespace(partition="long", account="proj7", time="1:00:00", max_parallel=8)
        cmd = slurm_backend.sbatch_command(args, 40, "/w/slurm", "/w/slurm/x.sh", "sweep")
        self.assertEqual(cmd[:5], ["sbatch", "--parsable", "--job-name=vbsim-sweep", "--array=0-39%8", "--ntasks=1"])
        self.assertIn("--output=/w/slurm/%A_%a.out", cmd)
        for option in ("--partition=long", "--account=proj7", "--time=1:00:00"):
            self.assertIn(option, cmd)
        self.assertEqual(cmd[-1], "/w/slurm/x.sh")
        bare = types.SimpleNamespace(partition=None, account=None, time=None, max_parallel=None)
        self.assertIn("--array=0-0", slurm_backend.sbatch_command(bare, 1, "/w", "/w/x.sh", "t"))

    def test_tasks_are_reported_by_status(self):
        with tempfile.TemporaryDirectory() as d:
            with open(f"{d}/7_0.status", "w") as f:
                json.dump({"task": 0, "points": 2, "failures": []}, f)
            with open(f"{d}/7_1.status", "w") as f:
                json.dump({"task": 1, "points": 2, "failures": ["point x: command failed (1): vbsim"]}, f)
            failures = slurm_backend.task_failures(7, 3, d)
            self.assertEqual(len(failures), 2)
            self.assertTrue(failures[0].startswith(f"task 7_1 failed 1 of 2 points; log {d}/7_1.out"))
            self.assertTrue(failures[1].startswith("task 7_2 ended without a status"))

    def test_the_manifest_splits_points_into_task_shares(self):
        with tempfile.TemporaryDirectory() as d:
            points = [Point(str(i), [["true"]], f"{d}/{i}") for i in range(5)]
            manifest, script = slurm_backend.write_job_files(points, 2, d, "t")
            m = json.loads(read(manifest))
            self.assertEqual(m["per_task"], 2)
            self.assertEqual([p["label"] for p in m["points"]], ["0", "1", "2", "3", "4"])
            text = read(script)
            self.assertIn("point_task.py", text)
            self.assertIn('"$SLURM_ARRAY_TASK_ID"', text)
            self.assertTrue(os.access(script, os.X_OK))


class ProgressTest(unittest.TestCase):
    def test_the_line_by_hand(self):
        # 25 of 100 points in 5 s: 5 points/s, 75 left: 15 s.
        self.assertEqual(progress_text("sweep", 25, 100, "points", 5.0),
                         "sweep   25.0%  25/100 points  5 points/s  ETA 0:15")
        self.assertEqual(progress_text("sweep", 1, 4, "points", 2.0),
                         "sweep   25.0%  1/4 points  0.5 points/s  ETA 0:06")
        self.assertEqual(clock_text(3601.2), "1:00:02")


class ProvenanceTest(unittest.TestCase):
    def test_a_stamped_png_keeps_valid_chunks_and_carries_the_provenance(self):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "c.png")
            fig = plt.figure(figsize=(1, 1))
            fig.savefig(path)
            plt.close(fig)
            before = plt.imread(path)
            provenance.stamp_png(path, {"program": "t", "inputs": []})
            data = read(path, "rb")
            chunks, at = [], 8
            while at < len(data):
                (length,) = struct.unpack(">I", data[at:at + 4])
                kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
                (crc,) = struct.unpack(">I", data[at + 8 + length:at + 12 + length])
                self.assertEqual(crc, zlib.crc32(kind + body) & 0xffffffff, kind)
                chunks.append((kind, body))
                at += 12 + length
            self.assertEqual(chunks[0][0], b"IHDR")
            self.assertEqual(chunks[1][0], b"iTXt")
            key, _, rest = chunks[1][1].partition(b"\0")
            self.assertEqual(key, b"vbsim-provenance")
            self.assertEqual(json.loads(rest[4:]), {"program": "t", "inputs": []})
            self.assertTrue((plt.imread(path) == before).all())

    def test_a_markdown_comment_never_holds_a_double_dash(self):
        text = provenance.provenance_comment({"command": ["sweep.py", "--only", "x"]})
        body = text[len("<!-- "):-len(" -->\n")]
        self.assertNotIn("--", body)
        self.assertEqual(json.loads(body[len("vbsim-provenance "):])["command"][1], "--only")


if __name__ == "__main__":
    unittest.main()
