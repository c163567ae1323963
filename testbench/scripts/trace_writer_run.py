#!/usr/bin/python3
"""The Python trace writer (scripts/trace_writer.py) through vbsim itself.

Usage: trace_writer_run.py VBSIM_BINARY

- The bundled trace rewritten with the writer, in both forms, converts to the
  same binary records as vbsim's own conversion and replays to the same verdicts.
- Values that are hard to write (-0, the float32 tie 0x15ae43fd, subnormals,
  FLT_MAX, every optional field) come back bit for bit through `vbsim convert`.
- Errors name the place and field; an interrupted `with` block leaves no file.
- The example of docs/trace-format.md runs and passes `vbsim check`.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import numpy as np  # noqa: E402

from read_binary_trace import read_binary_trace  # noqa: E402
from trace_writer import TraceWriteError, TraceWriter  # noqa: E402

VBSIM = None
BUNNY_TRACE = os.path.join(ROOT, "traces", "bunny", "paths.jsonl")


def vbsim(*args, cwd=None):
    r = subprocess.run([VBSIM, *args], capture_output=True, text=True, cwd=cwd)
    if r.returncode != 0:
        raise AssertionError(f"vbsim {' '.join(args)} exited {r.returncode}: {r.stdout}{r.stderr}")
    return r.stdout + r.stderr


def f32_bits(values):
    return np.asarray(values, dtype=np.float32).view(np.uint32).tolist()


def replay_verdicts(trace, tmp):
    stats = os.path.join(tmp, os.path.basename(trace) + ".stats.json")
    vbsim("replay", "-q", trace, "--method", "validity-bit", "--stats", stats)
    with open(stats) as f:
        s = json.load(f)
    return s["rays"], s["verdicts"], {k: v["verdicts"] for k, v in s["by_kind"].items()}


class BundledTraceRewritten(unittest.TestCase):
    def test_both_forms_match_vbsim_and_replay_the_same(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.relpath(os.path.join(ROOT, "traces", "bunny", "bunny.obj"), tmp)
            with open(BUNNY_TRACE) as f:
                header = json.loads(f.readline())
                rays = [json.loads(line) for line in f if line.strip()]
            for name in ("py.jsonl", "py.vbt"):
                with TraceWriter(os.path.join(tmp, name), scene=scene, generator=header.get("generator"),
                                 description=header.get("description"), light=header.get("light")) as w:
                    for r in rays:
                        expect = r.get("expect")
                        w.ray(id=r["id"], o=r["o"], d=r["d"], parent=r.get("parent", -1),
                              kind=r.get("kind", "primary"), tmin=r.get("tmin", 0.0),
                              tmax=np.inf if r.get("tmax") is None else r["tmax"],
                              parent_prim=r.get("parent_prim", -1), parent_t=r.get("parent_t"),
                              parent_uv=r.get("parent_uv"), parent_ns=r.get("parent_ns"), sign=r.get("sign"),
                              expect=None if expect is None else (expect["prim"], expect.get("t")))
            reference = os.path.join(tmp, "ref.vbt")
            vbsim("convert", BUNNY_TRACE, "-o", reference)
            from_text = os.path.join(tmp, "from_text.vbt")
            vbsim("convert", os.path.join(tmp, "py.jsonl"), "-o", from_text)
            ref_header, ref = read_binary_trace(reference)
            ref_header.pop("provenance", None)  # what vbsim convert ran on: not a field of the writers'
            for path in (os.path.join(tmp, "py.vbt"), from_text):
                h, recs = read_binary_trace(path)
                h.pop("provenance", None)
                self.assertEqual(h, ref_header, path)
                self.assertEqual(recs.tobytes(), ref.tobytes(), path)  # byte for byte
            self.assertEqual(len(ref), 1008)
            expected = replay_verdicts(BUNNY_TRACE, tmp)
            for name in ("py.jsonl", "py.vbt"):
                self.assertEqual(replay_verdicts(os.path.join(tmp, name), tmp), expected, name)


class HardValues(unittest.TestCase):
    def test_bit_exact_through_vbsim_convert(self):
        tie = np.array([0x15AE43FD], dtype="<u4").view("<f4")[0]
        rays = [
            dict(id=0, o=(-0.0, tie, 1e-45), d=(3.4028235e38, -tie, 0.1), expect=(7, 0.1)),
            dict(id=3, parent=0, kind="refract", o=(1, 2, 3), d=(0, 0, -1), tmin=1e-4, tmax=123456.79,
                 parent_prim=7, parent_t=17.314083, parent_uv=(0.47456515, -0.0), parent_ns=(0, 1e-38, -1),
                 sign=1, expect=(-1, None)),
            dict(id=4, parent=3, kind="shadow", o=(16777216, 1e16, 100000), d=(0, 1, 0), tmax=1, parent_prim=2,
                 sign=0),
        ]
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("h.jsonl", "h.vbt"):
                with TraceWriter(os.path.join(tmp, name), scene="s.ply", transform=[1e-5] * 16) as w:
                    for r in rays:
                        w.ray(**r)
            for name in ("h.jsonl", "h.vbt"):
                out = os.path.join(tmp, name + ".converted.vbt")
                vbsim("convert", os.path.join(tmp, name), "-o", out)
                header, recs = read_binary_trace(out)
                self.assertEqual(f32_bits(header["transform"]), f32_bits([1e-5] * 16))
                self.assertEqual(recs["id"].tolist(), [0, 3, 4])
                self.assertEqual(f32_bits(recs["o"][0]), f32_bits((-0.0, tie, 1e-45)), name)
                self.assertEqual(f32_bits(recs["d"][0]), f32_bits((3.4028235e38, -tie, 0.1)), name)
                self.assertEqual(f32_bits(recs["parent_uv"][1]), f32_bits((0.47456515, -0.0)), name)
                self.assertEqual(f32_bits(recs["tmax"]), f32_bits((np.inf, 123456.79, 1)), name)
                self.assertEqual(recs["expect_prim"].tolist(), [7, -1, -1])
                self.assertEqual(recs["expect_t"][0], 0.1)
                self.assertEqual(recs["kind"].tolist(), [0, 2, 4])
                self.assertEqual(recs["flags"].tolist(), [0x18, 0x2F, 0x20])
            _, a = read_binary_trace(os.path.join(tmp, "h.vbt"))
            _, b = read_binary_trace(os.path.join(tmp, "h.jsonl.converted.vbt"))
            self.assertEqual(a.tobytes(), b.tobytes())


class Errors(unittest.TestCase):
    def test_errors_name_place_and_field(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "e.jsonl")
            with self.assertRaisesRegex(TraceWriteError, r"e\.jsonl: line 3: field 'd'"):
                with TraceWriter(path, scene="s.ply") as w:
                    w.ray(id=0, o=(0, 0, 5), d=(0, 0, -1))
                    w.ray(id=1, o=(0, 0, 5), d=(0, 0, 0))
            self.assertEqual(os.listdir(tmp), [])  # nothing left that looks complete
            with self.assertRaisesRegex(TraceWriteError, r"record 0: field 'parent'.*precede"):
                with TraceWriter(os.path.join(tmp, "e.vbt"), scene="s.ply") as w:
                    w.ray(id=0, parent=5, o=(0, 0, 5), d=(0, 0, -1), parent_prim=1)
            with self.assertRaisesRegex(TraceWriteError, r"field 'expect.t'"):
                with TraceWriter(path, scene="s.ply") as w:
                    w.ray(id=0, o=(0, 0, 5), d=(0, 0, -1), expect=(-1, 2.0))
            self.assertEqual(os.listdir(tmp), [])

    def test_what_every_reader_refuses(self):
        """A duplicate id and a child of kind primary: refused by the writer as vbsim's readers refuse them."""
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("d.jsonl", "d.vbt"):
                path = os.path.join(tmp, name)
                with self.assertRaisesRegex(TraceWriteError, r"(line 4|record 2): field 'id': 0 was given before"):
                    with TraceWriter(path, scene="s.ply") as w:
                        w.ray(id=0, o=(0, 0, 5), d=(0, 0, -1))
                        w.ray(id=1, o=(0, 0, 5), d=(0, 0, -1))
                        w.ray(id=0, o=(0, 0, 5), d=(0, 0, -1))
                with self.assertRaisesRegex(TraceWriteError, r"field 'id': 3 was given before"):  # not in order
                    with TraceWriter(path, scene="s.ply") as w:
                        for i in (5, 3, 9, 4, 3):
                            w.ray(id=i, o=(0, 0, 5), d=(0, 0, -1))
                with self.assertRaisesRegex(TraceWriteError, r"field 'kind': primary .*parent 0"):
                    with TraceWriter(path, scene="s.ply") as w:
                        w.ray(id=0, o=(0, 0, 5), d=(0, 0, -1))
                        w.ray(id=1, parent=0, o=(0, 0, 5), d=(0, 0, -1), parent_prim=1)
                self.assertEqual(os.listdir(tmp), [])
            # What the writer refuses, vbsim refuses too (the text form written by hand).
            path = os.path.join(tmp, "h.jsonl")
            with open(path, "w") as f:
                f.write('{"format":"vbsim-trace","version":1,"scene":"s.ply"}\n{"id":0,"o":[0,0,5],"d":[0,0,-1]}\n'
                        '{"id":1,"parent":0,"o":[0,0,5],"d":[0,0,-1],"parent_prim":1}\n')
            r = subprocess.run([VBSIM, "check", path], capture_output=True, text=True)
            self.assertEqual(r.returncode, 1)
            self.assertIn("h.jsonl:3: field 'kind': primary", r.stdout + r.stderr)

    def test_a_value_beyond_float32_is_one_clear_error(self):
        """1e39 overflows float32: the field's error, and no numpy warning before it."""
        code = ("import sys; sys.path.insert(0, %r)\n"
                "from trace_writer import TraceWriter, TraceWriteError\n"
                "try:\n"
                "    with TraceWriter(%r, scene='s.ply') as w:\n"
                "        w.ray(id=0, o=(1e39, 0, 0), d=(0, 0, -1))\n"
                "except TraceWriteError as e:\n"
                "    print(e)\n")
        with tempfile.TemporaryDirectory() as tmp:
            r = subprocess.run([sys.executable, "-W", "error", "-c",
                                code % (os.path.join(ROOT, "scripts"), os.path.join(tmp, "b.jsonl"))],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(r.stderr, "")
            self.assertIn("line 2: field 'o'", r.stdout)
            self.assertIn("not finite", r.stdout)


class OneModule(unittest.TestCase):
    def test_the_writer_stands_alone_and_says_when_numpy_is_missing(self):
        with tempfile.TemporaryDirectory() as tmp:
            with open(os.path.join(ROOT, "scripts", "trace_writer.py")) as src, \
                    open(os.path.join(tmp, "trace_writer.py"), "w") as dst:
                dst.write(src.read())
            # Alone in a directory: it imports and writes a trace that vbsim reads.
            code = ("from trace_writer import TraceWriter\n"
                    "with TraceWriter('a.vbt', scene='s.ply') as w:\n"
                    "    w.ray(id=0, o=(0, 0, 5), d=(0, 0, -1), incomplete=('instance', 'filter'))\n")
            r = subprocess.run([sys.executable, "-c", code], cwd=tmp, capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            vbsim("convert", os.path.join(tmp, "a.vbt"), "-o", os.path.join(tmp, "a.jsonl"))
            with open(os.path.join(tmp, "a.jsonl")) as f:
                self.assertEqual(json.loads(f.read().splitlines()[1])["incomplete"], ["instance", "filter"])
            # Without numpy: an ImportError that says what to do.
            code = "import sys; sys.modules['numpy'] = None\nimport trace_writer\n"
            r = subprocess.run([sys.executable, "-c", code], cwd=tmp, capture_output=True, text=True)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("trace_writer needs numpy", r.stderr)
            self.assertIn("python3-numpy", r.stderr)


class ReferenceLayout(unittest.TestCase):
    def test_layout_2_reads_with_its_dtype(self):
        """A trace with reference answers converts to layout 2; read_binary_trace picks its dtype."""
        from read_binary_trace import describe
        with tempfile.TemporaryDirectory() as tmp:
            text = os.path.join(tmp, "r.jsonl")
            with open(text, "w") as f:
                f.write('{"format":"vbsim-trace","version":1,"scene":"s.ply","reference":"Embree"}\n'
                        '{"id":0,"o":[0,0,5],"d":[0,0,-1],"reference":{"prim":3,"t":1.5}}\n'
                        '{"id":1,"kind":"shadow","o":[0,0,5],"d":[0,0,1],"reference":{"occluded":true}}\n')
            vbt = os.path.join(tmp, "r.vbt")
            vbsim("convert", text, "-o", vbt)
            header, recs = read_binary_trace(vbt)
            self.assertEqual(header["reference"], "Embree")
            self.assertEqual(recs.dtype.itemsize, 104)
            self.assertEqual(recs["reference_prim"].tolist(), [3, -2])
            self.assertEqual(describe(recs[0])["reference"], {"prim": 3, "t": 1.5})
            self.assertEqual(describe(recs[1])["reference"], {"occluded": True})


def doc_example(language):
    """The code block after '<!-- example: LANGUAGE writer -->' in docs/trace-format.md."""
    with open(os.path.join(ROOT, "docs", "trace-format.md")) as f:
        text = f.read()
    m = re.search(r"<!-- example: %s writer -->\s*```\w+\n(.*?)```" % language, text, re.S)
    assert m, f"no {language} writer example in docs/trace-format.md"
    return m.group(1)


class DocExample(unittest.TestCase):
    def test_the_documented_example_runs_and_checks_clean(self):
        code = doc_example("python")
        self.assertLessEqual(len([l for l in code.splitlines() if l.strip()]), 10)
        with tempfile.TemporaryDirectory() as tmp:
            os.symlink(os.path.join(ROOT, "traces", "bunny", "bunny.obj"), os.path.join(tmp, "bunny.obj"))
            cwd = os.getcwd()
            os.chdir(tmp)
            try:
                exec(compile(code, "docs/trace-format.md", "exec"), {})
            finally:
                os.chdir(cwd)
            trace = os.path.join(tmp, "example.vbt")
            out = vbsim("check", trace)
            self.assertIn("2 rays, 0 errors, 2 warnings (missing_expect 2)", out)
            vbsim("oracle", trace, "-o", os.path.join(tmp, "scored.vbt"))
            self.assertIn("0 errors, 0 warnings", vbsim("check", "--strict", os.path.join(tmp, "scored.vbt")))
            vbsim("replay", os.path.join(tmp, "scored.vbt"))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: trace_writer_run.py VBSIM_BINARY")
    VBSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main()
