# Blender (Debian 12's 3.4) renders every age of an exported strip series under two lights:
#   blender -b --factory-startup --python-exit-code 1 --python blender_strip_series.py -- \
#       SERIES.glb OUT_DIR SIZE SAMPLES SKY.exr SUN_X SUN_Y SUN_Z SUN_IRRADIANCE
# For each material variant (an age) it writes OUT_DIR/<variant>_white.exr, the strip under
# a uniform white world of radiance 1, and OUT_DIR/<variant>_sky.exr, under SKY.exr and its
# sun, as patina-render's scene shows them to a strip facing up: the strip faces Blender's
# -Y (glTF's +Z after the importer's turn), so patina-render's world (+Y up) is turned half a
# turn about X onto Blender's: (x, y, z) -> (x, -y, -z). The sky image is patina-render's
# lat-long (top row the zenith, the centre column looking along -z, u = 0.75 towards +x),
# looked up through that turn; the sun is a sun lamp of the same irradiance and 0.53 degrees.
import math
import os
import sys

import bpy
import mathutils
import numpy

# Blender 3.4's glTF importer calls numpy.bool, which Debian 12's numpy 1.24 removed; the
# builtin bool is what it meant (as in blender_gltf_check.py).
if not hasattr(numpy, "bool"):
    numpy.bool = bool

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_render  # noqa: E402


def sky_world(scene, sky_path):
    w = bpy.data.worlds.new("sky")
    w.use_nodes = True
    nodes, links = w.node_tree.nodes, w.node_tree.links
    background = nodes["Background"]
    coords = nodes.new("ShaderNodeTexCoord")  # in a world: the direction looked along
    unit = nodes.new("ShaderNodeVectorMath")
    unit.operation = "NORMALIZE"
    links.new(coords.outputs["Generated"], unit.inputs[0])
    xyz = nodes.new("ShaderNodeSeparateXYZ")
    links.new(unit.outputs["Vector"], xyz.inputs["Vector"])

    def math_node(op, a, b=None):
        n = nodes.new("ShaderNodeMath")
        n.operation = op
        for i, v in enumerate((a, b)):
            if v is None:
                continue
            if isinstance(v, float):
                n.inputs[i].default_value = v
            else:
                links.new(v, n.inputs[i])
        return n.outputs[0]

    # patina direction p = (b.x, -b.y, -b.z): u = 0.5 + atan2(p.x, -p.z) / 2 pi,
    # v = 0.5 + asin(p.y) / pi (Blender's image v runs up).
    u = math_node("ADD", math_node("DIVIDE", math_node("ARCTAN2", xyz.outputs["X"], xyz.outputs["Z"]),
                                   2.0 * math.pi), 0.5)
    v = math_node("ADD", math_node("DIVIDE", math_node("ARCSINE",
                                                      math_node("MULTIPLY", xyz.outputs["Y"], -1.0)),
                                   math.pi), 0.5)
    uv = nodes.new("ShaderNodeCombineXYZ")
    links.new(u, uv.inputs["X"])
    links.new(v, uv.inputs["Y"])
    image = nodes.new("ShaderNodeTexImage")
    image.image = bpy.data.images.load(sky_path)
    image.image.colorspace_settings.name = "Linear"
    image.extension = "EXTEND"
    image.interpolation = "Closest"
    links.new(uv.outputs["Vector"], image.inputs["Vector"])
    links.new(image.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = 1.0
    scene.world = w


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    asset, out_dir = args[0], args[1]
    size, samples = int(args[2]), int(args[3])
    sky_path = args[4]
    sun = mathutils.Vector((float(args[5]), -float(args[6]), -float(args[7])))
    irradiance = float(args[8])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=asset)
    scene = bpy.context.scene
    obj = next(o for o in bpy.data.objects if o.type == "MESH")
    blender_render.ortho_camera(scene, (0.0, -1.0, 0.0), max(obj.dimensions.x, obj.dimensions.z))
    variants = [v.name for v in scene.gltf2_KHR_materials_variants_variants]
    lamp = bpy.data.lights.new("sun", "SUN")
    lamp.energy = irradiance
    lamp.angle = math.radians(0.53)
    sun_object = bpy.data.objects.new("sun", lamp)
    sun_object.rotation_euler = sun.normalized().to_track_quat("Z", "Y").to_euler()
    for i, name in enumerate(variants):
        scene.gltf2_active_variant = i
        bpy.ops.scene.gltf2_display_variant()
        for light in ("white", "sky"):
            if light == "white":
                if sun_object.name in scene.collection.objects:
                    scene.collection.objects.unlink(sun_object)
                blender_render.world(scene, 1.0)
            else:
                scene.collection.objects.link(sun_object)
                sky_world(scene, sky_path)
            blender_render.render_exr(scene, os.path.join(out_dir, f"{name}_{light}.exr"),
                                      size, samples)


main()
