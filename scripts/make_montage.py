#!/usr/bin/python3
"""Side-by-side montage of `vbsim render` for every self-intersection method.

One row per scene, one column per method: the shaded image above, the error
image below (acne red, leaks blue, both yellow, correct pixels grey), titled
with the method and the acne / leak pixel counts. Writes docs/results/montage.png
by default. Needs /usr/bin/python3 with numpy and matplotlib, and a built
build/vbsim.

A SCENE argument is one of:
  NAME        a `vbsim gen` scenario: generated into WORK/NAME, its trace
              WORK/NAME/NAME.jsonl (or the first trace there) is rendered
  NAME:CASE   the same, rendering WORK/NAME/CASE.jsonl
  FILE        a scene (ply, obj, ...) or a trace (.jsonl, .vbt)
  FILE@K      the scene FILE moved 2^K along x, y and z by a float32 instance
              transform (a header-only trace written into WORK)
and may end in "+inside" (traces only): the camera sits at the origin of the
trace's first camera ray and looks along it (60 degree field of view), with a
point light at the camera, to look into a crevice instead of at its outside.
Without SCENE arguments: DEFAULT_SCENES (terminator, crevice and far-instance);
each one whose scenario the vbsim build does not know is replaced by its
stand-in (STAND_INS below) and the figure says so.

    /usr/bin/python3 scripts/make_montage.py                # the committed montage
    /usr/bin/python3 scripts/make_montage.py terminator:terminator-s32 traces/bunny/bunny.obj@20
"""
import argparse
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.patches as mpatches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import provenance  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

METHODS = ["none", "tmin", "primid", "offset-normal", "offset-direction", "offset-adaptive",
           "offset-errbound", "validity-bit", "validity-bit:vb-policy=vote", "sign-only", "shading-position",
           "shading-position-always", "reverse-shadow"]

DEFAULT_SCENES = ["terminator:terminator-s8", "crevice:crevice-5deg+inside", "far-instance"]

# Used for a default scene whose scenario does not exist yet (files relative
# to the repository; "paths" is a scenario).
STAND_INS = {
    "terminator": "traces/bunny/bunny.obj",
    "crevice": "paths",
    "far-instance": "traces/bunny/bunny.obj@16",
}

# The error image's legend (model/render/render_colours.h).
LEGEND = [("acne (self hit)", (255, 40, 40)), ("leak (missed, false hit)", (0, 170, 255)),
          ("both", (255, 215, 0)), ("correct (grey)", (128, 128, 128))]


class SceneError(Exception):
    pass


def run(cmd):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def generate(vbsim, work, name, rays):
    """Runs `vbsim gen NAME`; returns its output directory, or None when the
    scenario is unknown to this build."""
    out = os.path.join(work, name)
    r = run([vbsim, "gen", name, "--rays", str(rays), "-o", out])
    if r.returncode != 0:
        if "unknown scenario" in r.stdout:
            return None
        raise SceneError(f"vbsim gen {name} failed:\n{r.stdout}")
    return out


def pick_trace(directory, name, case):
    wanted = os.path.join(directory, (case or name) + ".jsonl")
    if os.path.exists(wanted):
        return wanted
    if case:
        raise SceneError(f"{wanted}: no such trace")
    traces = sorted(f for f in os.listdir(directory) if f.endswith(".jsonl"))
    if not traces:
        raise SceneError(f"{directory}: vbsim gen wrote no trace")
    return os.path.join(directory, traces[0])


def far_trace(work, path, k):
    """A header-only trace placing `path` 2^k away along (1, 1, 1)."""
    scene = os.path.abspath(path)
    if not os.path.exists(scene):
        raise SceneError(f"{path}: no such scene file")
    s = float(2 ** k)
    header = {"format": "vbsim-trace", "version": 1, "scene": scene,
              "transform": [1, 0, 0, s, 0, 1, 0, s, 0, 0, 1, s, 0, 0, 0, 1],
              "description": f"{os.path.basename(path)} moved 2^{k} along x, y and z"}
    out = os.path.join(work, f"{os.path.splitext(os.path.basename(path))[0]}-far{k}.jsonl")
    with open(out, "w") as f:
        f.write(json.dumps(header) + "\n")
    return out


def resolve(vbsim, work, spec, rays):
    """(label, file to render) for one SCENE argument, or None for an unknown scenario."""
    if "@" in spec:
        path, k = spec.rsplit("@", 1)
        try:
            k = int(k)
        except ValueError:
            raise SceneError(f"{spec}: expected FILE@K with an integer K")
        return f"{os.path.basename(path)} at 2^{k}", far_trace(work, path, k)
    if os.path.isfile(spec):
        return os.path.basename(spec), spec
    name, _, case = spec.partition(":")
    directory = generate(vbsim, work, name, rays)
    if directory is None:
        return None
    return spec, pick_trace(directory, name, case)


def inside_view(trace):
    """Render options for "+inside": camera on the trace's first camera ray,
    a point light at the camera."""
    with open(trace) as f:
        for line in f:
            ray = json.loads(line) if line.strip() and not line.startswith("#") else {}
            if "d" in ray and ray.get("parent", -1) == -1:
                eye, d = ray["o"], ray["d"]
                target = [eye[i] + d[i] for i in range(3)]
                fmt = lambda v: ",".join(repr(float(x)) for x in v)  # noqa: E731
                return ["--camera", fmt(eye + target), "--fov", "60", "--light", "point:" + fmt(eye)]
    raise SceneError(f"{trace}: no camera ray for '+inside'")


def render(vbsim, scene, options, method, size, work, tag):
    img = os.path.join(work, f"{tag}-{method}.png")
    err = os.path.join(work, f"{tag}-{method}-errors.png")
    stats = os.path.join(work, f"{tag}-{method}.json")
    r = run([vbsim, "render", scene, "--method", method, "--size", size, "-o", img,
             "--errors", err, "--stats", stats, "--quiet"] + options)
    if r.returncode != 0:
        raise SceneError(f"vbsim render {scene} --method {method} failed:\n{r.stdout}")
    with open(stats) as f:
        pixels = json.load(f)["pixels"]
    return mpimg.imread(img), mpimg.imread(err), pixels


def montage(rows, methods, out):
    cols = len(methods)
    h, w = rows[0][1][0][0].shape[:2]
    cell_w, cell_h = 1.45, 1.45 * h / w + 0.22
    figsize = (max(cell_w * cols + 0.6, 4.8), cell_h * 2 * len(rows) + 0.9)
    fig, axes = plt.subplots(2 * len(rows), cols, figsize=figsize, squeeze=False)
    for r, (label, cells) in enumerate(rows):
        for c, (img, err, pixels) in enumerate(cells):
            top, bottom = axes[2 * r][c], axes[2 * r + 1][c]
            top.imshow(img, interpolation="nearest")
            bottom.imshow(err, interpolation="nearest")
            top.set_title(methods[c].replace("validity-bit:vb-policy=vote", "validity-bit (vote)"), fontsize=8)
            bottom.set_title(f"acne {pixels['acne']}  leak {pixels['leak']}", fontsize=7)
            for ax in (top, bottom):
                ax.set_xticks([])
                ax.set_yticks([])
        axes[2 * r][0].set_ylabel(label, fontsize=8)
        axes[2 * r + 1][0].set_ylabel("errors", fontsize=8)
    handles = [mpatches.Patch(color=[v / 255 for v in rgb], label=name) for name, rgb in LEGEND]
    ncol = len(handles) if cols >= 5 else 2
    fig.legend(handles=handles, loc="lower center", ncol=ncol, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.03 if ncol > 2 else 0.09, 1, 1), h_pad=0.4, w_pad=0.3)
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=100)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="*", help="scenario names, NAME:CASE, scene or trace files, FILE@K")
    ap.add_argument("--vbsim", default=os.path.join(ROOT, "build", "vbsim"))
    ap.add_argument("--methods", default=",".join(METHODS), help="comma-separated methods (columns)")
    ap.add_argument("--size", default="160x120", help="image size WxH of each render")
    ap.add_argument("--rays", type=int, default=200, help="--rays for vbsim gen")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "montage"), help="scratch directory")
    ap.add_argument("-o", "--out", default=os.path.join(ROOT, "docs", "results", "montage.png"))
    a = ap.parse_args()
    if not os.access(a.vbsim, os.X_OK):
        sys.exit(f"make_montage: {a.vbsim}: not built (run scripts/setup.sh)")
    os.makedirs(a.work, exist_ok=True)
    methods = [m for m in a.methods.split(",") if m]

    specs = a.scenes or DEFAULT_SCENES
    rows, scenes_used = [], []
    try:
        for spec in specs:
            inside = spec.endswith("+inside")
            spec = spec[:-len("+inside")] if inside else spec
            resolved = resolve(a.vbsim, a.work, spec, a.rays)
            name = spec.split(":")[0]
            if resolved is None and not a.scenes and name in STAND_INS:
                inside = False
                stand_in = STAND_INS[name]
                if stand_in.split("@")[0].endswith(".obj"):
                    stand_in = os.path.join(ROOT, stand_in)
                label, scene = resolve(a.vbsim, a.work, stand_in, a.rays)
                resolved = (f"{label}\n(stand-in for {name})", scene)
                print(f"make_montage: no scenario '{name}' yet; using {STAND_INS[name]}")
            if resolved is None:
                raise SceneError(f"{spec}: not a file and not a scenario of {a.vbsim}")
            label, scene = resolved
            scenes_used.append(scene)
            options = inside_view(scene) if inside else []
            label += "\n(inside)" if inside else ""
            tag = os.path.splitext(os.path.basename(scene))[0]
            cells = [render(a.vbsim, scene, options, m, a.size, a.work, tag) for m in methods]
            for m, (_, _, px) in zip(methods, cells):
                print(f"{label.splitlines()[0]:<28} {m:<24} acne {px['acne']:>6}  leak {px['leak']:>6}")
            rows.append((label, cells))
    except SceneError as e:
        sys.exit(f"make_montage: {e}")
    montage(rows, methods, a.out)
    provenance.stamp_png(a.out, provenance.script_provenance(os.path.abspath(a.vbsim), scenes_used))
    print(f"make_montage: wrote {a.out}")


if __name__ == "__main__":
    main()
