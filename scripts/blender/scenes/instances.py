"""A Cycles scene with instancing: one Suzanne mesh shared by four objects (linked data, so
Cycles builds one Embree scene and instances it), each moved and turned, on a ground plane,
with a point light (about 4,000 triangles). For scripts/blender_capture.py."""
import bpy

bpy.ops.wm.read_factory_settings(use_empty=True)
sc = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=12, location=(0, 0, 0))
bpy.ops.mesh.primitive_monkey_add(size=1.0, location=(-2.4, 0, 0.7))
mesh = bpy.context.object.data
for k in range(1, 4):
    o = bpy.data.objects.new(f"monkey{k}", mesh)
    o.location = (-2.4 + 1.6 * k, 0.3 * k, 0.7)
    o.rotation_euler = (0, 0, 0.4 * k)
    sc.collection.objects.link(o)
bpy.ops.object.light_add(type="POINT", location=(2, -3, 5))
bpy.context.object.data.energy = 1500
bpy.ops.object.camera_add(location=(0, -8, 3), rotation=(1.2, 0, 0))
sc.camera = bpy.context.object
