"""The workload suite's ray types, made with vbsim's own commands and split into
one trace per type (docs/suite.md, "Ray types").

Five sources per scene; the first four are reference runs (children from the
exact answers, so the rays do not depend on a method):
- `vbsim render --integrator mirror`: primary rays, shadow rays toward the
  point light, mirror (reflect) rays;
- `vbsim render --integrator path --bounces 3`: diffuse rays by bounce (1, 2,
  3: how many diffuse rays lie between the ray and its camera ray, plus one);
- `vbsim render --integrator ao`: ambient-occlusion rays, `--spp` occlusion
  queries (kind shadow) at each camera hit, cosine-distributed about the
  shading normal, `ao_radius` times the scene's bounding-box diagonal long;
- `vbsim render --integrator glass`: every surface a dielectric of index 1.5,
  one camera ray a pixel and at each hit its refraction (or, past the critical
  angle, its reflection), up to `glass_bounces` of them: the glass rays;
- `vbsim capture --strip-offsets -- pathtracer`: Embree's own path tracer
  (embree-tools) on the scene, one thread: the `pathtracer` type is its whole
  trace, camera rays, shadow rays and bounces with their parents (another
  renderer's ray distribution; its children follow Embree's answers).

A type's trace holds that type's rays only, each without its parent ray
(`parent` -1; `parent_prim`, `parent_t`, `parent_uv`, `parent_ns` kept): a
replay then takes each ray's intended origin at `parent_uv` on `parent_prim`
(docs/trace-format.md, "The exact answer"), and `vbsim oracle` fills in the
exact answers for that definition. The cycle-level model sees the type's rays
as independent queries, a wavefront renderer's queue of one kind.
"""
import json
import os

from trace_writer import TraceWriter

TYPES = ("primary", "shadow", "ao", "diffuse-1", "diffuse-2", "diffuse-3", "mirror", "glass", "pathtracer")
SOURCE_OF = {"primary": "mirror", "shadow": "mirror", "mirror": "mirror", "ao": "ao",
             "diffuse-1": "path", "diffuse-2": "path", "diffuse-3": "path", "glass": "glass",
             "pathtracer": "pathtracer"}


def source_commands(vbsim, scene_ply, light, opts, out_dir, camera):
    """The command that makes each source's trace, keyed by source name; `camera` is
    (eye, target, vertical fov in degrees) for Embree's path tracer."""
    size = f"{opts.width}x{opts.height}"
    light_arg = "point:" + ",".join(repr(float(x)) for x in light)
    render = [vbsim, "render", scene_ply, "-m", "none", "--children-from", "exact", "--size", size,
              "--light", light_arg, "-q"]
    return {
        "mirror": render + ["--integrator", "mirror", "-o", os.path.join(out_dir, "mirror.png"),
                            "--trace-out", os.path.join(out_dir, "mirror.jsonl")],
        "ao": render + ["--integrator", "ao", "--spp", str(opts.spp), "--ao-radius", repr(float(opts.ao_radius)),
                        "--seed", "1", "-o", os.path.join(out_dir, "ao.png"),
                        "--trace-out", os.path.join(out_dir, "ao.jsonl")],
        "path": render + ["--integrator", "path", "--bounces", "3", "--spp", str(opts.spp), "--seed", "1",
                          "-o", os.path.join(out_dir, "path.png"), "--trace-out", os.path.join(out_dir, "path.jsonl")],
        "glass": render + ["--integrator", "glass", "--bounces", str(opts.glass_bounces),
                           "-o", os.path.join(out_dir, "glass.png"), "--trace-out", os.path.join(out_dir, "glass.jsonl")],
        "pathtracer": _pathtracer_capture(vbsim, scene_ply, light, opts, out_dir, camera),
    }


def _pathtracer_capture(vbsim, scene_ply, light, opts, out_dir, camera):
    eye, target, fov = camera
    cap = os.path.join(out_dir, "pathtracer")
    return [vbsim, "capture", "--strip-offsets", "--allow-partial", "-o", cap, "--", "pathtracer",
            "-i", os.path.abspath(scene_ply), "--size", str(opts.width), str(opts.height), "--spp", str(opts.spp),
            "--ambientlight", "0.3", "0.3", "0.3", "--pointlight", *(repr(float(x)) for x in light),
            "300", "300", "300", "--threads", "1", "-o", os.path.join(cap, "image.ppm"),
            "--vp", *(repr(float(x)) for x in eye), "--vi", *(repr(float(x)) for x in target),
            "--vu", "0", "1", "0", "--fov", repr(float(fov))]


def source_trace(source, out_dir):
    if source == "pathtracer":
        return os.path.join(out_dir, "pathtracer", "trace.jsonl")
    return os.path.join(out_dir, source + ".jsonl")


def _type_of(ray, source, depth):
    kind = ray.get("kind", "primary")
    if source == "mirror":
        return {"primary": "primary", "shadow": "shadow", "reflect": "mirror"}.get(kind)
    if source == "path":
        return f"diffuse-{depth}" if kind == "diffuse" else None
    if source == "ao":
        return "ao" if kind == "shadow" else None
    return "glass" if kind in ("refract", "reflect") else None


def split(source, trace, wanted, out_dir, limit):
    """Writes OUT_DIR/TYPE.raw.jsonl for every type of `wanted` this source makes:
    its rays without parents and without `expect` (primary rays keep theirs),
    at most `limit` of them taken evenly over the trace. Returns {type: (path,
    rays in the source)}."""
    if source == "pathtracer":
        return _whole(trace, out_dir, limit)
    with open(trace) as f:
        header = json.loads(f.readline())
        scene = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(trace)), header["scene"]))
        depth, picked = {}, {t: [] for t in wanted}
        for line in f:
            if not line.strip() or line.startswith("#"):
                continue
            ray = json.loads(line)
            parent = ray.get("parent", -1)
            kind = ray.get("kind", "primary")
            d = 0 if parent < 0 else depth.get(parent, 0) + (1 if kind == "diffuse" else 0)
            if kind in ("primary", "diffuse"):
                depth[ray["id"]] = d
            t = _type_of(ray, source, d)
            if t in picked:
                picked[t].append(ray)
    out = {}
    for t, rays in picked.items():
        if t not in SOURCE_OF or SOURCE_OF[t] != source:
            continue
        total = len(rays)
        if limit and total > limit:
            rays = [rays[(k * total) // limit] for k in range(limit)]
        path = os.path.join(out_dir, t + ".raw.jsonl")
        description = (f"suite ray type {t}: {len(rays)} of {total} rays of {os.path.basename(trace)}, "
                       "each without its parent ray")
        with TraceWriter(path, scene=os.path.relpath(scene, out_dir), light=header.get("light"),
                         generator="scripts/suite.py", description=description,
                         transform=header.get("transform")) as w:
            for r in rays:
                fields = dict(r)
                if t != "primary":
                    fields["parent"] = -1
                    fields.pop("expect", None)
                expect = fields.pop("expect", None)
                if expect is not None:
                    fields["expect"] = (expect["prim"], expect.get("t"))
                w.ray(**fields)
        out[t] = (path, total)
    return out


def _whole(trace, out_dir, limit):
    """The `pathtracer` type: the captured trace's rays with their parents, the
    first `limit` of them (parents precede children, so a cut keeps every kept
    ray's parent). Embree's answers (`reference`) are left in the capture."""
    with open(trace) as f:
        header = json.loads(f.readline())
        rays = [json.loads(line) for line in f if line.strip() and not line.startswith("#")]
    total = len(rays)
    if limit and total > limit:
        rays = rays[:limit]
    scene = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(trace)), header["scene"]))
    path = os.path.join(out_dir, "pathtracer.raw.jsonl")
    description = (f"suite ray type pathtracer: {len(rays)} of {total} rays Embree's pathtracer traced "
                   "(vbsim capture --strip-offsets), with their parents")
    with TraceWriter(path, scene=os.path.relpath(scene, out_dir), generator="scripts/suite.py",
                     description=description) as w:
        for r in rays:
            fields = {k: v for k, v in r.items() if k not in ("reference",)}
            w.ray(**fields)
    return {"pathtracer": (path, total)}
