#!/usr/bin/python3
"""scripts/subdivide_mesh.py on hand-made meshes: the four children of a triangle
at its edge midpoints (shared between neighbours), quads fanned, counts after N
rounds, the area kept, and a provenance comment naming the input."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "subdivide_mesh.py")


def run(text, rounds):
    with tempfile.TemporaryDirectory() as tmp:
        src, out = os.path.join(tmp, "in.obj"), os.path.join(tmp, "out.obj")
        with open(src, "w") as f:
            f.write(text)
        subprocess.run([sys.executable, SCRIPT, src, str(rounds), "-o", out], check=True, capture_output=True)
        with open(out) as f:
            lines = f.read().splitlines()
    v = [tuple(float(x) for x in l.split()[1:]) for l in lines if l.startswith("v ")]
    f = [tuple(int(x) - 1 for x in l.split()[1:]) for l in lines if l.startswith("f ")]
    comments = [l for l in lines if l.startswith("#")]
    return v, f, comments


def area(v, t):
    a, b, c = (v[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    return 0.5 * sum(x * x for x in n) ** 0.5


class SubdivideTest(unittest.TestCase):
    def test_one_triangle_once(self):
        v, f, comments = run("v 0 0 0\nv 4 0 0\nv 0 2 0\nf 1 2 3\n", 1)
        self.assertEqual(len(f), 4)
        self.assertEqual(v[3:], [(2.0, 0.0, 0.0), (2.0, 1.0, 0.0), (0.0, 1.0, 0.0)])
        self.assertEqual(f[0], (0, 3, 5))  # the corner at v0 with its two midpoints
        self.assertAlmostEqual(sum(area(v, t) for t in f), 4.0)
        prov = json.loads(comments[1].split(" ", 2)[2])
        self.assertEqual(prov["program"], "subdivide_mesh.py")
        self.assertEqual(prov["inputs"][0]["bytes"], len("v 0 0 0\nv 4 0 0\nv 0 2 0\nf 1 2 3\n"))

    def test_a_quad_is_fanned_and_midpoints_are_shared(self):
        v, f, _ = run("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1//1 2//2 3//3 4//4\n", 2)
        self.assertEqual(len(f), 2 * 16)
        # 2 triangles sharing a diagonal: 4 + 5 midpoints in round one, then 16 more edges split.
        self.assertEqual(len(v), 4 + 5 + 16)
        self.assertAlmostEqual(sum(area(v, t) for t in f), 1.0)


if __name__ == "__main__":
    unittest.main()
