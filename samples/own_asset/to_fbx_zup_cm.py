# samples/own_asset: the project's statue as an artist's FBX from 3ds Max or Maya would bring
# it: Z up, Y forward, in centimetres (FBX GlobalSettings UpAxis 2, UnitScaleFactor 1).
#   blender -b --factory-startup --python-exit-code 1 --python to_fbx_zup_cm.py -- IN.obj OUT.fbx
import sys

import bpy

source, target = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.context.scene.unit_settings.system = "METRIC"
bpy.context.scene.unit_settings.scale_length = 0.01  # 1 Blender unit = 1 cm
bpy.ops.wm.obj_import(filepath=source, forward_axis="NEGATIVE_Z", up_axis="Y")
for obj in bpy.context.selected_objects:
    obj.scale = (100.0, 100.0, 100.0)  # metres of the OBJ to centimetres
bpy.ops.object.transform_apply(location=False, rotation=True, scale=True)
bpy.ops.export_scene.fbx(filepath=target, axis_up="Z", axis_forward="Y", apply_unit_scale=True)
