# The uv unwrap `patina-texgen unwrap` runs in Blender (Debian 12's 3.4), headless:
#   blender -b --factory-startup --python-exit-code 1 --python unwrap.py -- \
#       IN.glb OUT.glb METHOD MARGIN ANGLE_DEG
# IN.glb is the user's mesh as Patina read it (+Y up, metres, the artist's uvs as
# TEXCOORD_0 where it has them, its materials by name). Every mesh gets a new uv map,
# "patina", made by Blender's Smart UV Project (METHOD smart: islands split where faces
# meet at more than ANGLE_DEG) or Lightmap Pack (METHOD lightmap: one island per face, for
# lightmaps), with all meshes packed together into one unit tile, MARGIN (a fraction of the
# tile) between islands. OUT.glb holds the meshes with their uv maps in order (the
# artist's first, "patina" last) and their materials. The last line printed is
# "patina-unwrap: uv set N": the index of "patina" among the uv sets.
import math
import sys

import numpy

# Blender 3.4's glTF importer calls numpy.bool, which numpy 1.24 (Debian 12) removed after
# deprecating it; the builtin bool is what the alias meant.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    source, target, method = args[0], args[1], args[2]
    margin, angle = float(args[3]), float(args[4])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=source)
    objects = [o for o in bpy.data.objects if o.type == "MESH"]
    if not objects:
        raise RuntimeError("the mesh file holds no mesh")
    # Meshes shared by several objects get a copy each: each object's uvs are its own.
    for o in objects:
        if o.data.users > 1:
            o.data = o.data.copy()
    index = None
    for o in objects:
        layer = o.data.uv_layers.new(name="patina")
        if layer is None:
            raise RuntimeError(f"mesh '{o.name}' already has the most uv sets Blender keeps (8)")
        o.data.uv_layers.active = layer
        here = len(o.data.uv_layers) - 1
        if index is not None and here != index:
            raise RuntimeError("some meshes have uvs and others none: give them all uvs, or "
                               "none")
        index = here

    bpy.ops.object.select_all(action="DESELECT")
    for o in objects:
        o.select_set(True)
    bpy.context.view_layer.objects.active = objects[0]
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    if method == "smart":
        bpy.ops.uv.smart_project(angle_limit=math.radians(angle), island_margin=margin,
                                 area_weight=0.0, correct_aspect=True, scale_to_bounds=False)
    elif method == "lightmap":
        bpy.ops.uv.lightmap_pack(PREF_CONTEXT="ALL_FACES", PREF_PACK_IN_ONE=True,
                                 PREF_NEW_UVLAYER=False, PREF_BOX_DIV=12,
                                 PREF_MARGIN_DIV=max(0.001, margin * 10.0))
    else:
        raise RuntimeError(f"unknown method '{method}'")
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.ops.export_scene.gltf(filepath=target, export_format="GLB", export_texcoords=True,
                              export_normals=True, export_materials="EXPORT", export_yup=True,
                              export_apply=False)
    print(f"patina-unwrap: uv set {index}")


main()
