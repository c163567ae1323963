"""Materials for the scene scripts of scripts/blender/scenes/ (run inside Blender)."""
import bpy


def principled(name, **inputs):
    """A node material whose Principled BSDF takes `inputs` (socket name: value)."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    for k, v in inputs.items():
        bsdf.inputs[k].default_value = v
    return m
