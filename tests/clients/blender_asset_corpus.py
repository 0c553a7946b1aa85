# Blender (Debian 12's 3.4) writes the meshes an artist brings, in the conventions other
# programs use, for the tests of docs/your-asset.md; run by the tests as
#   blender -b --factory-startup --python-exit-code 1 --python blender_asset_corpus.py -- DIR
# Every asset is one "figure": a box 0.40 m wide (x), 0.30 m deep and 1.50 m tall, standing
# on the ground, with Blender's cube uvs (six faces, no overlap). Written into DIR:
#   figure_zup_cm.fbx  Z up, Y forward, 1 unit = 1 cm (as 3ds Max and Maya in cm write it):
#                      FBX GlobalSettings UpAxis 2, UnitScaleFactor 1
#   figure_zup_cm.dae  COLLADA <unit name="centimeter" meter="0.01"/>, <up_axis>Z_UP
#   figure_mm.glb      glTF of the figure modelled in millimetres (1500 units tall) and
#                      exported without conversion: glTF says metres, so it is 1.5 km tall
import os
import sys

import bpy


def figure(units_per_metre):
    bpy.ops.mesh.primitive_cube_add(size=1)
    obj = bpy.context.active_object
    obj.name = "figure"
    obj.scale = (0.40 * units_per_metre, 0.30 * units_per_metre, 1.50 * units_per_metre)
    obj.location = (0.0, 0.0, 0.75 * units_per_metre)
    bpy.ops.object.transform_apply(location=True, rotation=True, scale=True)
    return obj


def fresh_scene(scale_length):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    units = bpy.context.scene.unit_settings
    units.system = "METRIC"
    units.scale_length = scale_length


def main():
    out = sys.argv[sys.argv.index("--") + 1]
    os.makedirs(out, exist_ok=True)

    # 1 Blender unit = 1 cm: the FBX exporter writes UnitScaleFactor 1 (FBX counts in cm),
    # the COLLADA exporter <unit meter="0.01">; Blender's own axes are Z up.
    fresh_scene(0.01)
    figure(100.0)
    bpy.ops.export_scene.fbx(filepath=os.path.join(out, "figure_zup_cm.fbx"), axis_up="Z",
                             axis_forward="Y", apply_unit_scale=True)
    bpy.ops.wm.collada_export(filepath=os.path.join(out, "figure_zup_cm.dae"))

    # Millimetres in a glTF: its exporter writes Blender units as metres.
    fresh_scene(1.0)
    figure(1000.0)
    bpy.ops.export_scene.gltf(filepath=os.path.join(out, "figure_mm.glb"))


main()
