"""Runs inside Blender (blender -b [FILE.blend] --python render_cycles.py -- ARGS): builds the
scene from an optional scene script, then renders one frame with Cycles on the CPU, one thread,
a fixed seed and no denoiser, and writes the image without metadata (so that two renders of the
same scene are byte-identical). Used by scripts/blender_capture.py.

ARGS: --out IMAGE [--scene-script PY] [--size WxH] [--samples N] [--bounces N]
"""
import argparse
import runpy
import sys

import bpy


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles.py")
    p.add_argument("--out", required=True, help="the image to write (Radiance .hdr: float pixels, no metadata)")
    p.add_argument("--scene-script", help="a Python script that builds the scene in Blender")
    p.add_argument("--size", default="64x48", help="WxH pixels")
    p.add_argument("--samples", type=int, default=8)
    p.add_argument("--bounces", type=int, default=None, help="Cycles' max_bounces (default: the scene's)")
    return p.parse_args(argv)


def main():
    a = parse()
    if a.scene_script:
        runpy.run_path(a.scene_script, run_name="__main__")
    sc = bpy.context.scene
    if sc.camera is None:
        sys.exit("render_cycles.py: the scene has no camera")
    w, h = (int(x) for x in a.size.lower().split("x"))
    sc.render.engine = "CYCLES"
    sc.cycles.device = "CPU"
    sc.cycles.samples = a.samples
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.use_denoising = False
    sc.cycles.seed = 1
    if a.bounces is not None:
        sc.cycles.max_bounces = a.bounces
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 1
    sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = w, h, 100
    sc.render.use_persistent_data = False
    sc.render.use_stamp = False
    sc.render.metadata_input = "SCENE"
    for attr in dir(sc.render):  # every metadata field off: the date and render time would differ
        if attr.startswith("use_stamp_") and isinstance(getattr(sc.render, attr), bool):
            setattr(sc.render, attr, False)
    sc.render.image_settings.file_format = "HDR"  # Radiance RGBE: float pixels, no metadata to differ
    sc.render.filepath = a.out
    bpy.ops.render.render(write_still=True)


main()
