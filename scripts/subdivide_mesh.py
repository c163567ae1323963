#!/usr/bin/python3
"""Splits every triangle of an OBJ mesh into four (edge midpoints), N times,
for a larger workload of the same shape: 3,674 bunny triangles become 235,136
after three rounds. Reads `v` and `f` lines only (faces of three or more
vertices, `a`, `a/b`, `a//c` or `a/b/c`; polygons are fanned); writes `v` and
`f` lines, midpoints in float32 decimals that read back exactly.

    /usr/bin/python3 scripts/subdivide_mesh.py traces/bunny/bunny.obj 3 -o bunny235k.obj
"""
import argparse
import json
import os
import struct
import sys

from point_jobs import file_digest


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh")
    ap.add_argument("rounds", type=int)
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()
    vertices, faces = [], []
    with open(a.mesh) as f:
        for n, line in enumerate(f, 1):
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                vertices.append(tuple(f32(float(x)) for x in w[1:4]))
            elif w[0] == "f":
                idx = [int(x.split("/")[0]) for x in w[1:]]
                idx = [i - 1 if i > 0 else len(vertices) + i for i in idx]
                if len(idx) < 3:
                    sys.exit(f"{a.mesh}:{n}: a face needs three vertices")
                faces += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    for _ in range(a.rounds):
        mid = {}

        def midpoint(i, j):
            key = (min(i, j), max(i, j))
            if key not in mid:
                p, q = vertices[i], vertices[j]
                vertices.append(tuple(f32((p[k] + q[k]) / 2) for k in range(3)))
                mid[key] = len(vertices) - 1
            return mid[key]

        out = []
        for i, j, k in faces:
            a_, b_, c_ = midpoint(i, j), midpoint(j, k), midpoint(k, i)
            out += [(i, a_, c_), (a_, j, b_), (c_, b_, k), (a_, b_, c_)]
        faces = out
    prov = {"program": os.path.basename(sys.argv[0]), "command": [sys.executable] + sys.argv,
            "inputs": [{"path": os.path.relpath(a.mesh), "bytes": os.path.getsize(a.mesh),
                        "sha256": file_digest(a.mesh)}]}
    partial = a.out + ".partial"  # the mesh gets its name only when complete
    with open(partial, "w") as f:
        f.write(f"# {a.mesh} subdivided {a.rounds} times: {len(faces)} triangles\n")
        f.write("# vbsim-provenance " + json.dumps(prov, separators=(",", ":")) + "\n")
        for v in vertices:
            f.write("v %s %s %s\n" % tuple(repr(x) for x in v))
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
    os.replace(partial, a.out)
    print(f"{a.out}: {len(vertices)} vertices, {len(faces)} triangles")


if __name__ == "__main__":
    main()
