"""A small Cycles scene: a glass UV sphere, a metallic Suzanne subdivided once, a ground plane
and a point light (4,898 triangles). For scripts/blender_capture.py."""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from blender_materials import principled  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
sc = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=10, location=(0, 0, 0))
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, location=(-1.2, 0, 0.8))
bpy.context.object.data.materials.append(principled("glass", Transmission=1.0, Roughness=0.0))
bpy.ops.mesh.primitive_monkey_add(size=1.4, location=(1.2, 0, 0.9))
monkey = bpy.context.object
sub = monkey.modifiers.new("subdivision", "SUBSURF")
sub.levels = sub.render_levels = 1
monkey.data.materials.append(principled("metal", Metallic=1.0, Roughness=0.2))
bpy.ops.object.light_add(type="POINT", location=(2, -3, 5))
bpy.context.object.data.energy = 1500
bpy.ops.object.camera_add(location=(0, -7, 3), rotation=(1.2, 0, 0))
sc.camera = bpy.context.object
