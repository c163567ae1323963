#!/usr/bin/python3
"""scripts/suite.py --small end to end: every scene of the small tier prepared
with the triangle count its list entry states, every (scene, ray type) row
present with every method, rates within [0, 1] inside their intervals and equal
to their counts, cycles, energy and area on both presets, speeds against
Embree, and the page naming them; a list whose count is wrong is refused.

    /usr/bin/python3 suite_run.py PATH_TO_VBSIM
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "suite.py")
LIST = os.path.join(ROOT, "traces", "suite", "scenes.json")
TYPES = ("primary", "shadow", "ao", "diffuse-1", "diffuse-2", "diffuse-3", "mirror", "glass", "pathtracer")
VBSIM = None


def ply_faces(path):
    with open(path, "rb") as f:
        head = f.read(4096).split(b"end_header")[0].decode()
    return int(next(l for l in head.splitlines() if l.startswith("element face")).split()[2])


def trace_rays(path):
    with open(path) as f:
        return sum(1 for line in f if line.strip()) - 1


class SuiteSmallTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = os.path.join(cls.tmp.name, "suite")
        cls.page = os.path.join(cls.tmp.name, "page", "suite.md")
        os.makedirs(os.path.dirname(cls.page))
        cls.proc = subprocess.run(["/usr/bin/python3", SCRIPT, "--small", "--vbsim", VBSIM, "--out", cls.out,
                                   "--page", cls.page], capture_output=True, text=True)
        if cls.proc.returncode == 0:
            with open(os.path.join(cls.out, "results", "suite.json")) as f:
                cls.doc = json.load(f)
        with open(LIST) as f:
            cls.listed = {e["name"]: e for e in json.load(f)["scenes"]}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def setUp(self):
        self.assertEqual(self.proc.returncode, 0, self.proc.stdout + self.proc.stderr)

    def test_scenes_have_the_listed_triangles(self):
        small = [n for n, e in self.listed.items() if "small" in e["tiers"]]
        self.assertGreaterEqual(len(small), 2)
        self.assertEqual(sorted(s["name"] for s in self.doc["scenes"]), sorted(small))
        for s in self.doc["scenes"]:
            entry = self.listed[s["name"]]
            self.assertEqual(ply_faces(s["ply"]), entry["triangles"], s["name"])
            self.assertEqual(s["triangles"], entry["triangles"], s["name"])
            if entry["surface"] == "closed":
                self.assertEqual(s["boundary_edges"], 0, s["name"])
            if entry["surface"] == "open":
                self.assertGreater(s["boundary_edges"], 0, s["name"])
            for field in ("package", "licence"):
                self.assertTrue(s[field].strip(), s["name"])

    def test_every_scene_has_every_ray_type(self):
        got = {(r["scene"], r["type"]) for r in self.doc["results"]}
        want = {(s["name"], t) for s in self.doc["scenes"] for t in TYPES}
        self.assertEqual(got, want)
        for r in self.doc["results"]:
            self.assertGreater(r["rays"], 0, (r["scene"], r["type"]))
            self.assertLessEqual(r["rays"], r["source_rays"])

    def test_rates_counts_and_intervals(self):
        for r in self.doc["results"]:
            self.assertGreaterEqual(len(r["methods"]), 10, (r["scene"], r["type"]))
            names = {m["method"] for m in r["methods"]}
            self.assertTrue({"none", "validity-bit", "offset-errbound"} <= names)
            for m in r["methods"]:
                where = (r["scene"], r["type"], m["method"])
                if r["type"] == "pathtracer":  # its camera rays are in the trace, the secondary rows score the rest
                    self.assertTrue(0 < m["rays"] < r["rays"], where)
                else:
                    self.assertEqual(m["rays"], r["rays"], where)
                self.assertEqual(m["errors"], m["self_hit"] + m["false_hit"] + m["missed"], where)
                self.assertAlmostEqual(m["rate"], m["errors"] / m["rays"], places=9, msg=where)
                self.assertTrue(0.0 <= m["lower"] <= m["rate"] <= m["upper"] <= 1.0, where)
                self.assertGreater(m["upper"], 0.0, where)  # a zero count keeps an upper bound

    def test_pathtracer_type_is_a_capture_with_its_parents(self):
        # Embree's own path tracer, captured: camera rays, and children linked to their parents.
        runs = os.path.join(self.out, "runs")
        for r in self.doc["results"]:
            if r["type"] != "pathtracer":
                continue
            work = next(os.path.join(runs, d) for d in os.listdir(runs) if d.startswith(r["scene"] + "-"))
            with open(os.path.join(work, "pathtracer.jsonl")) as f:
                header = json.loads(f.readline())
                rays = [json.loads(line) for line in f if line.strip()]
            self.assertIn("pathtracer", header.get("description", ""), r["scene"])
            self.assertTrue(any(x.get("parent", -1) >= 0 for x in rays), r["scene"])
            self.assertTrue(any(x.get("kind") == "shadow" for x in rays), r["scene"])
            self.assertTrue(all("expect" in x for x in rays), r["scene"])  # through the oracle
            # Scored by kind as well: the kinds' rays add up to the trace's, each method's rows to its errors.
            kinds = {k: sum(1 for x in rays if x.get("kind", "primary") == k) for k in
                     ("primary", "shadow", "diffuse", "reflect", "refract")}
            for m in r["methods"]:
                split = [b for b in r["by_kind"] if (b["method"], b["tester"]) == (m["method"], m["tester"])]
                self.assertGreaterEqual(len(split), 2, (r["scene"], m["method"]))  # camera rays and shadow rays at least
                for b in split:  # scored rays of each kind: all of the trace's but any marked incomplete
                    self.assertTrue(0 < b["rays"] <= kinds[b["kind"]], (r["scene"], m["method"], b["kind"]))
                secondary = [b for b in split if b["kind"] != "primary"]
                self.assertEqual(sum(b["errors"] for b in secondary), m["errors"], (r["scene"], m["method"]))
                self.assertEqual(sum(b["rays"] for b in secondary), m["rays"], (r["scene"], m["method"]))
            with open(self.page) as f:
                self.assertIn(f"### {r['scene']}", f.read().split("## The `pathtracer` rays by kind")[1])

    def test_no_method_on_shadow_rays_shows_acne(self):
        # Unprotected shadow rays from the hit points re-hit their own surfaces somewhere.
        none = [m for r in self.doc["results"] if r["type"] == "shadow" for m in r["methods"] if m["method"] == "none"]
        self.assertGreater(sum(m["self_hit"] for m in none), 0)

    def test_cycles_energy_and_area_on_both_presets(self):
        for r in self.doc["results"]:
            for m in r["methods"]:
                if m["tester"] != "three-half-plane":
                    continue
                for p in ("small", "large"):
                    self.assertGreater(m[p]["cycles_per_ray"], 0, (r["scene"], r["type"], m["method"], p))
                    self.assertGreater(m[p]["energy_per_ray_pj"], 0)
                    self.assertGreater(m[p]["chip_mm2"], 0)
                self.assertGreater(m["large"]["chip_mm2"], m["small"]["chip_mm2"])

    def test_speed_and_memory(self):
        with open(os.path.join(self.out, "results", "suite-speed.csv")) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        self.assertEqual(len(rows), len(self.doc["results"]))
        for row in rows:
            for mode in ("functional", "cycle"):
                ours = float(row[f"{mode}_rays_per_s"])
                embree = float(row["embree_rays_per_s"] if mode == "functional" else row["cycle_embree_rays_per_s"])
                self.assertGreater(ours, 0)
                self.assertAlmostEqual(float(row[f"{mode}_ratio"]), ours / embree, delta=1e-3 * ours / embree)
            self.assertGreater(float(row["peak_rss_mb_score"]), 1.0)

    def test_traces_hold_the_counted_rays(self):
        runs = os.path.join(self.out, "runs")
        for r in self.doc["results"]:
            work = next(os.path.join(runs, d) for d in os.listdir(runs) if d.startswith(r["scene"] + "-"))
            path = os.path.join(work, r["type"] + ".jsonl")
            self.assertEqual(trace_rays(path), r["rays"], path)
            with open(path) as f:
                f.readline()
                first = json.loads(f.readline())
            self.assertIn("expect", first)
            if r["type"] not in ("primary", "pathtracer"):  # a capture keeps its trees, camera rays first
                self.assertEqual(first.get("parent", -1), -1)
                self.assertGreaterEqual(first["parent_prim"], 0)
            if r["type"] == "ao":  # an occlusion query a tenth of the bounding box's diagonal long
                self.assertEqual(first["kind"], "shadow")
                lo, hi = next(s["bounds"] for s in self.doc["scenes"] if s["name"] == r["scene"])
                diag = sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5
                length = first["tmax"] * sum(x * x for x in first["d"]) ** 0.5
                self.assertAlmostEqual(length / diag, 0.1, places=5)

    def test_the_far_scene_lies_far(self):
        far = next(s for s in self.doc["scenes"] if s["name"] == "far-wuson")
        near = next(s for s in self.doc["scenes"] if s["name"] == "wuson-15k")
        for lo_far, lo_near in zip(far["bounds"][0], near["bounds"][0]):
            self.assertAlmostEqual(lo_far - lo_near, 2.0 ** 16, delta=2.0 ** -6)

    def test_page_names_every_scene_and_type(self):
        with open(self.page) as f:
            page = f.read()
        for s in self.doc["scenes"]:
            self.assertIn(f"| {s['name']} | {s['triangles']:,} |", page)
        for t in TYPES:
            self.assertIn(f"### {t}", page)
        self.assertTrue(os.path.getsize(os.path.join(os.path.dirname(self.page), "suite.png")) > 0)


class SuiteListTest(unittest.TestCase):
    def test_a_wrong_count_is_refused(self):
        with open(LIST) as f:
            doc = json.load(f)
        entry = next(e for e in doc["scenes"] if e["name"] == "layers")
        entry["triangles"] += 1
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "scenes.json")
            with open(path, "w") as f:
                json.dump(doc, f)
            r = subprocess.run(["/usr/bin/python3", SCRIPT, "--list", path, "--scenes", "layers", "--prepare-only",
                                "--out", tmp], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("scene 'layers': 36864 triangles made, the list says 36865", r.stderr)


if __name__ == "__main__":
    VBSIM = sys.argv.pop(1)
    unittest.main()
