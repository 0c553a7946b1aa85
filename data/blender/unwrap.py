# The uv unwrap `patina-texgen unwrap` runs in Blender (Debian 12's 3.4), headless:
#   blender -b --factory-startup --python-exit-code 1 --python unwrap.py -- \
#       FOLDER METHOD MARGIN ANGLE_DEG
# FOLDER holds the surface as Patina welded it (texgen/unwrap/unwrap.cpp), as raw
# little-endian arrays: positions.f32 (x, y, z per vertex), triangles.u32 (three vertex
# indices per triangle). This script builds one Blender mesh of them, adds a uv map made by
# Smart UV Project (METHOD smart: islands split where faces meet at more than ANGLE_DEG) or
# Lightmap Pack (METHOD lightmap: a square per face, for lightmaps), packed into the unit
# tile with MARGIN (a fraction of the tile) between islands, and writes uvs.f32: the uv of
# every triangle corner in the triangles' order (u, v with v up). Raw arrays keep the
# triangles in their order and spare the glTF importer and exporter (seconds on a large
# mesh). Its last line is "patina-unwrap: done".
import math
import os
import sys

import bpy
import numpy


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    folder, method = args[0], args[1]
    margin, angle = float(args[2]), float(args[3])
    positions = numpy.fromfile(os.path.join(folder, "positions.f32"), dtype="<f4")
    triangles = numpy.fromfile(os.path.join(folder, "triangles.u32"), dtype="<u4")
    vertex_count, triangle_count = positions.size // 3, triangles.size // 3

    bpy.ops.wm.read_factory_settings(use_empty=True)
    mesh = bpy.data.meshes.new("surface")
    mesh.vertices.add(vertex_count)
    mesh.vertices.foreach_set("co", positions)
    mesh.loops.add(3 * triangle_count)
    mesh.loops.foreach_set("vertex_index", triangles)
    mesh.polygons.add(triangle_count)
    mesh.polygons.foreach_set("loop_start", numpy.arange(0, 3 * triangle_count, 3, dtype="<i4"))
    mesh.polygons.foreach_set("loop_total", numpy.full(triangle_count, 3, dtype="<i4"))
    mesh.update(calc_edges=True)
    if len(mesh.polygons) != triangle_count or len(mesh.loops) != 3 * triangle_count:
        raise RuntimeError("Blender changed the triangles it was given")
    layer = mesh.uv_layers.new(name="patina")
    obj = bpy.data.objects.new("surface", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)

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

    uvs = numpy.empty(2 * len(mesh.loops), dtype="<f4")
    mesh.uv_layers["patina"].data.foreach_get("uv", uvs)
    uvs.tofile(os.path.join(folder, "uvs.f32"))
    print("patina-unwrap: done")


main()
