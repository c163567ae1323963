#!/usr/bin/python3
"""Captures Blender's Cycles as a trace source: renders a scene script or a .blend file with
Cycles on the CPU (one thread, fixed seed, no denoiser) under `vbsim capture`, unmodified.

    scripts/blender_capture.py -o DIR [--scene-script PY] [--blend FILE] [--size WxH]
                               [--samples N] [--bounces N] [--check] [--vbsim PATH] [-- CAPTURE_OPTIONS]

DIR receives the capture (trace.jsonl, scene.ply, embree_hits.jsonl, capture.json) and the
image Cycles rendered under it (image.hdr). Without a scene the bundled
scripts/blender/scenes/glass_metal.py is rendered. Options after `--` go to `vbsim capture`
(e.g. --allow-partial, --binary, --link-ulps 16).

--check also renders the scene without the capture (image-plain.hdr) and verifies, writing
DIR/check.json: the two images are byte-identical; every ray of the trace is accounted for
(the capture's per-function counts sum to the trace's rays, nothing left out); the exact
oracle's answers (scored.jsonl) replayed with `primid` (Cycles' own primitive-ID exclusion)
give Cycles' answer on every ray (compare-reference); and which rays are unscored, by reason.
Exit status: 0 when the capture and every check pass, 1 otherwise (the reason printed).
Needs Debian's blender (scripts/setup.sh installs it); docs/capture.md, "Blender's Cycles".
"""
import argparse
import filecmp
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RENDER = os.path.join(ROOT, "scripts", "blender", "render_cycles.py")
DEFAULT_SCENE = os.path.join(ROOT, "scripts", "blender", "scenes", "glass_metal.py")


def parse(argv):
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("-o", "--out", required=True, help="the capture's directory")
    p.add_argument("--scene-script", help="a Python script that builds the scene in Blender")
    p.add_argument("--blend", help="a .blend file to render (its camera; a scene script runs after loading it)")
    p.add_argument("--size", default="64x48", help="WxH pixels [64x48]")
    p.add_argument("--samples", type=int, default=8, help="samples per pixel [8]")
    p.add_argument("--bounces", type=int, help="Cycles' max_bounces [the scene's]")
    p.add_argument("--check", action="store_true", help="render without capture too and verify the trace (above)")
    p.add_argument("--vbsim", default=None, help="the vbsim binary [build/vbsim, else scripts/vbsim]")
    a = p.parse_args(argv)
    a.capture_options = extra
    if not a.blend and not a.scene_script:
        a.scene_script = DEFAULT_SCENE
    for path in (a.blend, a.scene_script):
        if path and not os.path.isfile(path):
            p.error(f"no such file: {path}")
    if a.vbsim is None:
        built = os.path.join(ROOT, "build", "vbsim")
        a.vbsim = built if os.access(built, os.X_OK) else os.path.join(ROOT, "scripts", "vbsim")
    return a


def blender_command(a, image):
    cmd = ["blender", "-b", "--factory-startup", "--python-exit-code", "1"]
    if a.blend:
        cmd.append(a.blend)
    cmd += ["--python", RENDER, "--", "--out", image, "--size", a.size, "--samples", str(a.samples)]
    if a.scene_script:
        cmd += ["--scene-script", a.scene_script]
    if a.bounces is not None:
        cmd += ["--bounces", str(a.bounces)]
    return cmd


def run(cmd, what):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.stderr.write(r.stdout[-4000:] + r.stderr[-4000:])
        raise SystemExit(f"blender_capture: {what} failed (exit {r.returncode}): {' '.join(cmd)}")
    return r.stdout + r.stderr


def check(a, report):
    """The checks of --check; returns (ok, results)."""
    out = a.out
    plain = os.path.join(out, "image-plain.hdr")
    run(blender_command(a, plain), "the render without capture")
    res = {"image_identical": filecmp.cmp(plain, os.path.join(out, "image.hdr"), shallow=False)}
    by_function = sum(report["rays_by_function"].values())
    nc = report["not_captured"]
    res["rays"] = report["rays_in_trace"]
    res["rays_accounted"] = (by_function == report["rays_in_trace"] and nc["other_scene_or_commit"] == 0 and
                             nc["invalid"] == 0 and nc["other_process_rays"] == 0)
    trace = os.path.join(out, "trace.vbt" if "--binary" in a.capture_options else "trace.jsonl")
    scored = os.path.join(out, "scored.jsonl")
    hits = os.path.join(out, "primid.hits")
    run([a.vbsim, "oracle", trace, "-o", scored], "vbsim oracle")
    run([a.vbsim, "replay", scored, "--method", "primid", "--hits", hits], "vbsim replay --method primid")
    cmp_out = run([a.vbsim, "compare-reference", hits, os.path.join(out, "embree_hits.jsonl"), "-o",
                   os.path.join(out, "primid-differences.jsonl")], "vbsim compare-reference")
    differ = sum(1 for line in open(os.path.join(out, "primid-differences.jsonl")) if line.strip())
    res["primid_agrees_with_cycles"] = res["rays"] - differ
    res["primid_agreement"] = (res["rays"] - differ) / res["rays"] if res["rays"] else 0.0
    res["compare_reference"] = cmp_out.strip().splitlines()[-1] if cmp_out.strip() else ""
    res["incomplete_by_reason"] = report["incomplete"]["by_reason"]
    res["self_excluded"] = report.get("self_excluded", 0)
    ok = res["image_identical"] and res["rays_accounted"] and res["primid_agreement"] >= 0.999 and \
        "filter" not in res["incomplete_by_reason"]
    return ok, res


def main():
    a = parse(sys.argv[1:])
    os.makedirs(a.out, exist_ok=True)
    image = os.path.join(a.out, "image.hdr")
    cap = subprocess.run([a.vbsim, "capture", "-o", a.out, *a.capture_options, "--", *blender_command(a, image)],
                         capture_output=True, text=True)
    summary = "\n".join(l for l in cap.stdout.splitlines() if not l.startswith("Fra:"))
    report_path = os.path.join(a.out, "capture.json")
    print(summary[summary.find("vbsim capture:"):] if "vbsim capture:" in summary else summary)
    if cap.returncode != 0:
        sys.stderr.write(cap.stderr)
        if not os.path.isfile(report_path) or not a.check:
            return cap.returncode
    with open(report_path) as f:
        report = json.load(f)
    if not a.check:
        return 0
    ok, res = check(a, report)
    with open(os.path.join(a.out, "check.json"), "w") as f:
        json.dump(res, f, indent=2)
    print(f"blender_capture check: image identical {res['image_identical']}; rays {res['rays']} accounted "
          f"{res['rays_accounted']}; primid gives Cycles' answer on {res['primid_agrees_with_cycles']} "
          f"({100 * res['primid_agreement']:.3f}%); self-excluded {res['self_excluded']}; incomplete "
          f"{res['incomplete_by_reason'] or 'none'} -> {os.path.join(a.out, 'check.json')}")
    return 0 if ok and cap.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
