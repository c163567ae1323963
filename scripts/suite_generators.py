"""Generated scenes of the workload suite, each a function of its scene-list
settings returning (float32 vertices, int64 triangles); the same settings give
the same bytes. Coordinates are computed in double and rounded to float32 once.

- layers:    parallel wavy sheets a small gap apart, plus coincident copies
- far:       a mesh translated 2^k along (1,1,1) in world coordinates
- instances: copies of a mesh, rotated, scaled and placed, flattened into one
- floor:     a mesh standing on a thin closed slab (12 triangles)
"""
import numpy as np


def _sheet(grid, wave):
    """A unit square in x and z tessellated grid x grid (two triangles a cell),
    its height y a gentle wave; winding facing +y."""
    s = np.linspace(-1.0, 1.0, grid + 1)
    x, z = np.meshgrid(s, s, indexing="ij")
    y = wave * np.sin(2.5 * x) * np.cos(1.7 * z)
    verts = np.stack([x, y, z], -1).reshape(-1, 3)
    idx = np.arange((grid + 1) ** 2).reshape(grid + 1, grid + 1)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    tris = np.concatenate([np.stack([a, d, c], 1), np.stack([a, c, b], 1)])
    return verts, tris


def layers(sheets, grid, gap, coplanar, wave):
    """`sheets` copies of one wavy sheet, each `gap` above the last (thin
    layers), then `coplanar` copies of the first sheet with reversed winding:
    the even ones exact (every triangle in the plane of one of the first's),
    the odd ones the same wavy surface sampled half a cell further along x,
    whose facets cross the first sheet's at small angles (with `wave` 0 they
    too lie in its plane)."""
    base_v, base_t = _sheet(grid, wave)
    vs, ts = [], []
    for k in range(sheets):
        vs.append(base_v + np.array([0.0, k * gap, 0.0]))
        ts.append(base_t)
    cell = 2.0 / grid
    for k in range(coplanar):
        shift = cell / 2 if k % 2 else 0.0
        v = base_v.copy()
        v[:, 0] += shift
        if shift:  # stay in the plane of the first sheet: the wave evaluated at the new x
            v[:, 1] = wave * np.sin(2.5 * v[:, 0]) * np.cos(1.7 * v[:, 2])
        vs.append(v)
        ts.append(base_t[:, ::-1])
    return _join(vs, ts)


def far(verts, tris, offset_log2):
    """The mesh moved 2^k along (1,1,1), each coordinate rounded to float32."""
    moved = verts.astype(np.float64) + float(2 ** offset_log2)
    return moved.astype(np.float32), tris.copy()


def instances(verts, tris, count, seed):
    """`count` copies on a jittered cubic grid of side ceil(count^(1/3)) cells,
    each rotated about y by a random angle, scaled by 0.5 to 1.5 and centred
    in its cell (cells of twice the base mesh's bounding-sphere radius)."""
    rng = np.random.default_rng(seed)
    v = verts.astype(np.float64)
    centre = (v.min(0) + v.max(0)) / 2
    v = v - centre
    radius = float(np.sqrt((v * v).sum(1)).max())
    side = int(np.ceil(round(count ** (1.0 / 3.0), 9)))
    vs, ts = [], []
    for n in range(count):
        cell = np.array([n % side, (n // side) % side, n // (side * side)], dtype=np.float64)
        angle = rng.uniform(0.0, 2.0 * np.pi)
        scale = rng.uniform(0.5, 1.5)
        jitter = rng.uniform(-0.25, 0.25, 3)
        c, s = np.cos(angle), np.sin(angle)
        rot = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
        place = (cell + 0.5 + jitter * (1.5 - scale)) * 2.0 * radius * 1.5
        vs.append(v @ rot.T * scale + place)
        ts.append(tris)
    return _join(vs, ts)


def floor(verts, tris):
    """Adds a slab under the mesh: a closed box whose top face is the plane of
    the lowest vertex (y, up in vbsim's camera), twice the mesh's larger
    horizontal extent wide and a hundredth of its diagonal thick, so that
    paths bounce between the two and shadows fall on it; a closed mesh stays
    closed."""
    v = verts.astype(np.float64)
    lo, hi = v.min(0), v.max(0)
    centre = (lo + hi) / 2
    half = float(max(hi[0] - lo[0], hi[2] - lo[2]))
    thick = float(np.sqrt(((hi - lo) ** 2).sum())) / 100
    x0, x1, z0, z1 = centre[0] - half, centre[0] + half, centre[2] - half, centre[2] + half
    y0, y1 = lo[1] - thick, lo[1]
    box = np.array([[x, y, z] for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)])  # index 4x + 2y + z
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5],   # x = x0, x = x1
                      [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],   # y = y0, y = y1 (top, facing +y)
                      [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])  # z = z0, z = z1
    return _join([v, box], [tris, faces])


def _join(vs, ts):
    out_t, base = [], 0
    for v, t in zip(vs, ts):
        out_t.append(t + base)
        base += len(v)
    return np.concatenate(vs).astype(np.float32), np.concatenate(out_t).astype(np.int64)
