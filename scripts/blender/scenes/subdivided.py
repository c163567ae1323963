"""A large Cycles scene: Suzanne subdivided five times (Catmull-Clark at render:
1,007,618 triangles with the plane), smooth-shaded and glossy, on a ground plane, with a point light. For
scripts/blender_capture.py."""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from blender_materials import principled  # noqa: E402

bpy.ops.wm.read_factory_settings(use_empty=True)
sc = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=10, location=(0, 0, 0))
bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0, 0, 1.2))
monkey = bpy.context.object
bpy.ops.object.shade_smooth()
sub = monkey.modifiers.new("subdivision", "SUBSURF")
sub.levels = 1
sub.render_levels = 5
monkey.data.materials.append(principled("glossy", Metallic=0.6, Roughness=0.3))
bpy.ops.object.light_add(type="POINT", location=(2, -3, 5))
bpy.context.object.data.energy = 1500
bpy.ops.object.camera_add(location=(0, -7, 3), rotation=(1.2, 0, 0))
sc.camera = bpy.context.object
