#!/usr/bin/python3
"""Open3D's RaycastingScene (o3d.t.geometry.RaycastingScene.cast_rays) on the
bundled bunny: WIDTH x HEIGHT pinhole camera rays, for `vbsim capture` of an
application that loads Embree as Python loads an extension module (a local
library). Writes {"rays": N, "hits": H} to OUT.json.

    /usr/bin/python3 open3d_raycast.py MESH.obj OUT.json [WIDTH HEIGHT]
"""
import json
import sys

import numpy as np
import open3d as o3d


def main():
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    width, height = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) == 5 else (64, 48)
    mesh = o3d.io.read_triangle_mesh(sys.argv[1])
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.t.geometry.TriangleMesh.from_legacy(mesh))
    rays = scene.create_rays_pinhole(fov_deg=30, center=[0, 4.8, 0], eye=[0, 5, 25], up=[0, 1, 0],
                                     width_px=width, height_px=height)
    answer = scene.cast_rays(rays)
    hits = int(np.isfinite(answer["t_hit"].numpy()).sum())
    with open(sys.argv[2], "w") as f:
        json.dump({"rays": width * height, "hits": hits}, f)


if __name__ == "__main__":
    main()
