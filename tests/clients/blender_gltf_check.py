# Blender (Debian 12's 3.4) on a glTF asset written by `patina-texgen export`, run by the
# tests as
#   blender -b --factory-startup --python-exit-code 1 --python blender_gltf_check.py -- \
#       ASSET.glb REPORT.json [RENDER.exr VARIANT SIZE SAMPLES]
# It imports the asset with Blender's own glTF importer and writes REPORT.json: for every
# material, which image feeds each Principled BSDF input and in which colour space; the
# variant names; for each variant, the material the object shows once it is displayed.
# With RENDER.exr it displays VARIANT and renders the asset in Cycles, seen straight on by an
# orthographic camera that the strip fills, under a uniform white world (strength 1), with
# the Standard view transform: scene-linear Rec.709 values a test can compare.
import json
import os
import sys

import numpy

# Blender 3.4's glTF importer (io_scene_gltf2/blender/imp/gltf2_blender_mesh.py) calls
# numpy.bool, which numpy 1.24 (Debian 12) removed after deprecating it; the builtin bool
# is what the alias meant.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402
import mathutils  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_render  # noqa: E402


def linked_image(socket):
    """The image node feeding `socket`, through Separate RGB and Normal Map nodes."""
    if not socket.is_linked:
        return None
    node = socket.links[0].from_node
    while node.type != "TEX_IMAGE":
        inputs = [i for i in node.inputs if i.is_linked]
        if node.type == "NORMAL_MAP":
            inputs = [node.inputs["Color"]]
        if not inputs or not inputs[0].is_linked:
            return None
        node = inputs[0].links[0].from_node
    return node


def wiring(material):
    bsdf = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    out = {}
    for name in ("Base Color", "Metallic", "Roughness", "Normal", "Clearcoat",
                 "Clearcoat Roughness"):
        node = linked_image(bsdf.inputs[name])
        if node is not None and node.image is not None:
            out[name] = {"image": node.image.name,
                         "colorspace": node.image.colorspace_settings.name,
                         "size": list(node.image.size)}
    return out


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    asset, report_path = args[0], args[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=asset)
    scene = bpy.context.scene
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    if len(meshes) != 1:
        raise RuntimeError(f"expected one mesh object, found {len(meshes)}")
    obj = meshes[0]
    report = {
        "materials": {m.name: wiring(m) for m in bpy.data.materials if m.node_tree},
        "dimensions": list(obj.dimensions),
        "uv_maps": [layer.name for layer in obj.data.uv_layers],
        # World-space bounds in Blender's axes (Z up): the importer turns glTF's +Y up to +Z.
        "bounds_min": [min((obj.matrix_world @ mathutils.Vector(c))[k] for c in obj.bound_box)
                       for k in range(3)],
        "bounds_max": [max((obj.matrix_world @ mathutils.Vector(c))[k] for c in obj.bound_box)
                       for k in range(3)],
        "variants": [],
        "shown": [],
    }
    if "gltf2_KHR_materials_variants_variants" in scene.keys():
        report["variants"] = [v.name for v in scene.gltf2_KHR_materials_variants_variants]
        for i in range(len(report["variants"])):
            scene.gltf2_active_variant = i
            bpy.ops.scene.gltf2_display_variant()
            report["shown"].append(obj.material_slots[0].material.name)

    if len(args) > 2:
        render_path, variant, size, samples = args[2], args[3], int(args[4]), int(args[5])
        if variant in report["variants"]:
            scene.gltf2_active_variant = report["variants"].index(variant)
            bpy.ops.scene.gltf2_display_variant()
        report["rendered"] = obj.material_slots[0].material.name
        # The strip faces glTF's +Z, Blender's -Y after the importer's Y-up to Z-up turn.
        blender_render.ortho_camera(scene, (0.0, -1.0, 0.0),
                                    max(obj.dimensions.x, obj.dimensions.z))
        blender_render.world(scene, 1.0)
        blender_render.render_exr(scene, render_path, size, samples)

    with open(report_path, "w") as f:
        json.dump(report, f, indent=1)


main()
