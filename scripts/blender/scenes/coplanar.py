"""A Cycles scene of coplanar and overlapping geometry, where self-intersection methods are
tested hardest: a ground plane with a second plane exactly on it (z-fighting) and a decal
1e-4 above it, two cubes sharing a face, a thin slab (2e-3 thick) standing on the ground, a
glossy sphere and a point light (about 1,000 triangles). For scripts/blender_capture.py."""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from blender_materials import principled  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
sc = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=10, location=(0, 0, 0))
bpy.ops.mesh.primitive_plane_add(size=4, location=(0.5, 0.5, 0))          # exactly on the ground
bpy.context.object.data.materials.append(principled("red", **{"Base Color": (0.8, 0.1, 0.1, 1)}))
bpy.ops.mesh.primitive_plane_add(size=1.5, location=(-1.5, -0.5, 1e-4))   # a decal just above it
bpy.ops.mesh.primitive_cube_add(size=1, location=(-1.0, 1.0, 0.5))
bpy.ops.mesh.primitive_cube_add(size=1, location=(0.0, 1.0, 0.5))        # shares the face x = -0.5
bpy.context.object.data.materials.append(principled("glossy", Metallic=1.0, Roughness=0.05))
bpy.ops.mesh.primitive_cube_add(size=1, location=(1.4, -0.6, 0.6), scale=(0.8, 1e-3, 0.6))  # a thin slab
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(1.5, 1.2, 0.5))
bpy.context.object.data.materials.append(principled("mirror", Metallic=1.0, Roughness=0.0))
bpy.ops.object.light_add(type="POINT", location=(2, -3, 5))
bpy.context.object.data.energy = 1500
bpy.ops.object.camera_add(location=(0, -7, 3), rotation=(1.2, 0, 0))
sc.camera = bpy.context.object
