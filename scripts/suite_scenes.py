"""The workload suite's scene list (traces/suite/scenes.json, docs/suite.md) and
the preparation of each scene into the suite's cache as a binary PLY.

A prepared scene is DIR/NAME.ply with DIR/NAME.json beside it: the entry it was
made from (its `key`, a hash of the entry and of its base's key), triangles,
vertices, boundary edges and bounds. A scene whose `key` matches is not made
again. Preparation fails, naming the scene, when the triangle count differs
from the list's `triangles` or a `closed` scene has a boundary edge.
"""
import hashlib
import json
import math
import os
import tarfile

import suite_generators as gen
import suite_meshes as meshes

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DEFAULT_LIST = os.path.join(ROOT, "traces", "suite", "scenes.json")
CGAL_DATA = "/usr/share/doc/libcgal-demo/data.tar.gz"
SOURCE_KINDS = ("mesh", "cgal-data", "mesh-of", "layers", "far", "instances")
REQUIRED = ("name", "source", "origin", "package", "licence", "surface", "triangles", "tiers")


class SceneError(Exception):
    pass


def load_list(path=DEFAULT_LIST):
    """The entries of a scene list, checked: every field present, names unique,
    every base named before it is used, a known source kind."""
    with open(path) as f:
        doc = json.load(f)
    if doc.get("format") != "vbsim-suite-scenes" or doc.get("version") != 1:
        raise SceneError(f"{path}: not a version-1 vbsim-suite-scenes list")
    seen = {}
    for n, e in enumerate(doc["scenes"]):
        for field in REQUIRED:
            if field not in e:
                raise SceneError(f"{path}: scene {n}: no field '{field}'")
        if e["name"] in seen:
            raise SceneError(f"{path}: scene '{e['name']}' listed twice")
        kind = e["source"].get("kind")
        if kind not in SOURCE_KINDS:
            raise SceneError(f"{path}: scene '{e['name']}': source kind '{kind}' is not one of {SOURCE_KINDS}")
        base = e["source"].get("base")
        if base is not None and base not in seen:
            raise SceneError(f"{path}: scene '{e['name']}': base '{base}' is not listed before it")
        if e["surface"] not in ("closed", "open", "any"):
            raise SceneError(f"{path}: scene '{e['name']}': surface must be closed, open or any")
        seen[e["name"]] = e
    return doc["scenes"]


def select(entries, tier=None, names=None):
    out = entries
    if names:
        known = {e["name"] for e in entries}
        for n in names:
            if n not in known:
                raise SceneError(f"no scene '{n}' in the list")
        out = [e for e in out if e["name"] in names]
    if tier:
        out = [e for e in out if tier in e["tiers"]]
    return out


def _key(entry, by_name):
    base = entry["source"].get("base")
    text = json.dumps({"entry": entry, "base": _key(by_name[base], by_name) if base else None}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def _cgal_member(member):
    if not os.path.exists(CGAL_DATA):
        raise SceneError(f"{CGAL_DATA} is missing: install the suite's packages (scripts/setup.sh --suite)")
    with tarfile.open(CGAL_DATA) as tar:
        text = tar.extractfile(member).read().decode()
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".off", delete=False) as f:
        f.write(text)
    try:
        return meshes.read_off(f.name)
    finally:
        os.unlink(f.name)


def _build(entry, by_name, cache, log):
    src = entry["source"]
    kind = src["kind"]
    if kind in ("mesh-of", "far", "instances"):
        base_path = prepare(by_name[src["base"]], by_name, cache, log)["ply"]
        verts, tris = meshes.read_ply(base_path)
    if kind == "mesh":
        path = os.path.join(ROOT, src["path"])
        if not os.path.exists(path):
            raise SceneError(f"scene '{entry['name']}': {path} is missing (package {entry['package']}; "
                             "scripts/setup.sh --suite installs the suite's packages)")
        verts, tris = meshes.read_mesh(path)
    elif kind == "cgal-data":
        verts, tris = _cgal_member(src["member"])
    elif kind == "layers":
        verts, tris = gen.layers(src["sheets"], src["grid"], src["gap"], src["coplanar"], src["wave"])
    elif kind == "far":
        verts, tris = gen.far(verts, tris, src["offset_log2"])
    elif kind == "instances":
        verts, tris = gen.instances(verts, tris, src["count"], src["seed"])
    if src.get("subdivide"):
        verts, tris = meshes.subdivide(verts, tris, src["subdivide"])
    if src.get("floor"):
        verts, tris = gen.floor(verts, tris)
    return verts, tris


def prepare(entry, by_name, cache, log=print):
    """Makes (or finds) the scene's PLY; returns its metadata."""
    os.makedirs(cache, exist_ok=True)
    name = entry["name"]
    ply, meta_path = os.path.join(cache, name + ".ply"), os.path.join(cache, name + ".json")
    key = _key(entry, by_name)
    if os.path.exists(meta_path) and os.path.exists(ply):
        with open(meta_path) as f:
            meta = json.load(f)
        if meta.get("key") == key:
            return meta
    log(f"suite: preparing {name}")
    verts, tris = _build(entry, by_name, cache, log)
    if len(tris) != entry["triangles"]:
        raise SceneError(f"scene '{name}': {len(tris)} triangles made, the list says {entry['triangles']}")
    open_edges = meshes.boundary_edges(tris, len(verts))
    if entry["surface"] == "closed" and open_edges:
        raise SceneError(f"scene '{name}': listed as closed, {open_edges} boundary edges")
    if entry["surface"] == "open" and not open_edges:
        raise SceneError(f"scene '{name}': listed as open, no boundary edge")
    lo, hi = meshes.bounds(verts)
    partial = ply + ".partial"
    meshes.write_ply(partial, verts, tris, comment=f"vbsim suite scene {name}, {entry['package']}, {entry['licence']}")
    os.replace(partial, ply)
    meta = {"name": name, "key": key, "ply": ply, "triangles": int(len(tris)), "vertices": int(len(verts)),
            "boundary_edges": open_edges, "bounds": [lo, hi], "bytes": os.path.getsize(ply)}
    with open(meta_path + ".partial", "w") as f:
        json.dump(meta, f, indent=1)
    os.replace(meta_path + ".partial", meta_path)
    return meta


def pathtracer_camera(meta, fov=45.0):
    """Eye, target and vertical field of view for Embree's path tracer, framed as
    `vbsim render` frames a scene: the bounds' centre as the target, the eye along
    (0.35, 0.6, 1) from it, far enough that the bounding sphere fills the view."""
    lo, hi = meta["bounds"]
    centre = [(l + h) / 2 for l, h in zip(lo, hi)]
    radius = sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5 / 2
    dist = radius / math.sin(math.radians(fov) / 2)
    way = (0.35, 0.6, 1.0)
    norm = sum(x * x for x in way) ** 0.5
    return [c + dist * w / norm for c, w in zip(centre, way)], centre, fov


def point_light(meta):
    """A point light above, left of and in front of the scene: the bounds'
    centre plus (-0.6, 1, 0.4) times the bounds' diagonal."""
    lo, hi = meta["bounds"]
    diag = sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5
    return [(l + h) / 2 + k * diag for l, h, k in zip(lo, hi, (-0.6, 1.0, 0.4))]
