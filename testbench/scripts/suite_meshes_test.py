#!/usr/bin/python3
"""The workload suite's meshes: subdivision gives scripts/subdivide_mesh.py's
triangles (same order, same float32 corners), the PLY round trip is exact, the
boundary count tells closed from open, and the generators make the counts the
scene list states."""
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import suite_generators as gen  # noqa: E402
import suite_meshes as meshes  # noqa: E402

WUSON = os.path.join(ROOT, "traces", "wuson", "WusonOBJ.obj")


def corners(verts, tris):
    return verts[tris].reshape(len(tris), 9)


class SuiteMeshesTest(unittest.TestCase):
    def test_subdivision_matches_subdivide_mesh(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "w.obj")
            subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "subdivide_mesh.py"), WUSON, "1", "-o", out],
                           check=True, capture_output=True)
            ref = corners(*meshes.read_obj(out))
        v, t = meshes.subdivide(*meshes.read_obj(WUSON), 1)
        self.assertEqual(len(t), 4 * 3732)
        self.assertTrue(np.array_equal(corners(v, t), ref))

    def test_ply_round_trip_is_exact(self):
        v, t = meshes.subdivide(*meshes.read_obj(WUSON), 1)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "w.ply")
            meshes.write_ply(path, v, t, comment="test")
            v2, t2 = meshes.read_ply(path)
            self.assertEqual(meshes.ply_triangle_count(path), len(t))
        self.assertTrue(np.array_equal(v, v2))
        self.assertTrue(np.array_equal(t, t2))

    def test_boundary_edges(self):
        tetra = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
        self.assertEqual(meshes.boundary_edges(tetra, 4), 0)
        self.assertEqual(meshes.boundary_edges(tetra[:3], 4), 3)
        v, t = meshes.subdivide(np.eye(4, 3, dtype=np.float32), tetra, 2)
        self.assertEqual((len(v), len(t)), (4 + 6 + 24, 64))
        self.assertEqual(meshes.boundary_edges(t, len(v)), 0)

    def test_generators(self):
        v, t = gen.layers(sheets=3, grid=4, gap=1e-3, coplanar=2, wave=0.1)
        self.assertEqual(len(t), 4 * 4 * 2 * 5)
        self.assertEqual(v.dtype, np.float32)
        # the first coplanar copy is the first sheet with every triangle reversed
        n = 32
        self.assertTrue(np.array_equal(v[t[3 * n:4 * n]], v[t[:n]][:, ::-1]))
        v, t = gen.far(np.zeros((3, 3), np.float32) + 0.1, np.array([[0, 1, 2]]), 20)
        self.assertEqual(float(v[0, 0]), float(np.float32(2.0 ** 20 + 0.1)))
        base_v, base_t = meshes.read_obj(WUSON)
        v, t = gen.instances(base_v, base_t, 8, seed=1)
        self.assertEqual(len(t), 8 * len(base_t))
        self.assertEqual(meshes.boundary_edges(t, len(v)), 8 * meshes.boundary_edges(base_t, len(base_v)))
        v2, t2 = gen.instances(base_v, base_t, 8, seed=1)
        self.assertTrue(np.array_equal(v, v2))
        # the floor: 12 more triangles, a closed slab whose top is the lowest vertex's plane, facing up
        tetra = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
        tv = np.array([[0, 1, 0], [1, 2, 0], [0, 2, 1], [0, 3, 0]], np.float32)
        v, t = gen.floor(tv, tetra)
        self.assertEqual(len(t), 16)
        self.assertEqual(meshes.boundary_edges(t, len(v)), 0)
        self.assertEqual(float(v[4:, 1].max()), 1.0)
        top = [f for f in t[4:] if (v[f][:, 1] == 1.0).all()]
        self.assertEqual(len(top), 2)
        for f in top:
            a, b, c = v[f].astype(float)
            self.assertGreater(np.cross(b - a, c - a)[1], 0)


if __name__ == "__main__":
    unittest.main()
