"""Triangle meshes for the workload suite, held as numpy arrays: float32 vertices
(n, 3) and int64 triangles (m, 3). Reads OFF and OBJ (positions and faces only;
polygons fanned from their first vertex, as vbsim numbers them), writes binary
little-endian PLY (exact float32, the triangles in order), subdivides at edge
midpoints as scripts/subdivide_mesh.py does (same children, same float32
midpoints), and counts boundary edges (0: a closed mesh)."""
import numpy as np


def _fan(polys):
    """Triangles of polygons given as index lists, fanned from the first vertex."""
    tris = []
    for p in polys:
        tris += [(p[0], p[k], p[k + 1]) for k in range(1, len(p) - 1)]
    return tris


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#", 1)[0].split()]
    if not words or words[0] != "OFF":
        raise ValueError(f"{path}: not an OFF file")
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = np.array(words[at:at + 3 * nv], dtype=np.float64).reshape(nv, 3)
    at += 3 * nv
    polys = []
    for _ in range(nf):
        k = int(words[at])
        polys.append([int(w) for w in words[at + 1:at + 1 + k]])
        at += 1 + k
    tris = np.array(_fan(polys), dtype=np.int64).reshape(-1, 3)
    return verts.astype(np.float32), tris


def read_obj(path):
    verts, polys = [], []
    with open(path, encoding="latin-1") as f:  # names in some files are not UTF-8
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append([float(x) for x in w[1:4]])
            elif w[0] == "f":
                idx = [int(x.split("/")[0]) for x in w[1:]]
                polys.append([i - 1 if i > 0 else len(verts) + i for i in idx])
    tris = np.array(_fan(polys), dtype=np.int64).reshape(-1, 3)
    return np.array(verts, dtype=np.float32), tris


def read_mesh(path):
    if path.endswith(".off"):
        return read_off(path)
    if path.endswith(".obj"):
        return read_obj(path)
    if path.endswith(".ply"):
        return read_ply(path)
    raise ValueError(f"{path}: the suite reads OFF, OBJ and its own binary PLY")


def write_ply(path, verts, tris, comment=None):
    """Binary little-endian PLY: float x y z, faces as uchar count + int indices."""
    head = ["ply", "format binary_little_endian 1.0"]
    if comment:
        head.append("comment " + comment)
    head += [f"element vertex {len(verts)}", "property float x", "property float y", "property float z",
             f"element face {len(tris)}", "property list uchar int vertex_indices", "end_header"]
    face = np.zeros(len(tris), dtype=[("n", "u1"), ("i", "<i4", 3)])
    face["n"] = 3
    face["i"] = tris
    with open(path, "wb") as f:
        f.write(("\n".join(head) + "\n").encode())
        f.write(np.ascontiguousarray(verts, dtype="<f4").tobytes())
        f.write(face.tobytes())


def read_ply(path):
    """Reads back what write_ply writes (and nothing else)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode().splitlines()
    nv = int(next(l for l in head if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in head if l.startswith("element face")).split()[2])
    verts = np.frombuffer(data, dtype="<f4", count=3 * nv, offset=end).reshape(nv, 3)
    face = np.frombuffer(data, dtype=[("n", "u1"), ("i", "<i4", 3)], count=nf, offset=end + 12 * nv)
    if nf and not (face["n"] == 3).all():
        raise ValueError(f"{path}: only triangles are read back")
    return verts.copy(), face["i"].astype(np.int64)


def ply_triangle_count(path):
    """The face count a PLY header declares (without reading the body)."""
    with open(path, "rb") as f:
        head = f.read(65536)
    for line in head.split(b"\n"):
        if line.startswith(b"element face"):
            return int(line.split()[2])
        if line == b"end_header":
            break
    raise ValueError(f"{path}: no face element")


def _edge_keys(tris, nverts):
    a = tris[:, [0, 1, 2]].reshape(-1)
    b = tris[:, [1, 2, 0]].reshape(-1)
    return np.minimum(a, b) * nverts + np.maximum(a, b)


def subdivide(verts, tris, rounds):
    """Each triangle (i, j, k) becomes (i, a, c), (a, j, b), (c, b, k), (a, b, c),
    a, b, c the float32 midpoints of ij, jk, ki (shared between neighbours)."""
    for _ in range(rounds):
        n = len(verts)
        keys = _edge_keys(tris, n)
        uniq, inv = np.unique(keys, return_inverse=True)
        lo, hi = uniq // n, uniq % n
        mids = ((verts[lo].astype(np.float64) + verts[hi].astype(np.float64)) / 2).astype(np.float32)
        m = (inv.reshape(-1, 3) + n)
        a, b, c = m[:, 0], m[:, 1], m[:, 2]
        i, j, k = tris[:, 0], tris[:, 1], tris[:, 2]
        tris = np.stack([np.stack([i, a, c], 1), np.stack([a, j, b], 1),
                         np.stack([c, b, k], 1), np.stack([a, b, c], 1)], 1).reshape(-1, 3)
        verts = np.concatenate([verts, mids])
    return verts, tris


def boundary_edges(tris, nverts):
    """Edges used by one triangle only (by vertex index): 0 for a closed mesh."""
    _, counts = np.unique(_edge_keys(tris, nverts), return_counts=True)
    return int((counts == 1).sum())


def bounds(verts):
    v = verts.astype(np.float64)
    return v.min(0).tolist(), v.max(0).tolist()
