# Blender (Debian 12's 3.4) on an OpenVDB stone volume written by `patina-texgen export`:
#   blender -b --factory-startup --python-exit-code 1 --python blender_vdb_check.py -- \
#       VOLUME.vdb REPORT.json RENDER.exr SIZE SAMPLES
# Imports the file as a Volume object, loads its grids and writes REPORT.json with their
# names and types and the object's bounds; then renders it in Cycles with a Principled
# Volume whose density is the `density` grid (the extinction, 1/m, as written) and whose
# colour is the `color` grid, lit by a sun against a black world, so that any light in
# RENDER.exr is light the volume scattered.
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_render  # noqa: E402


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    vdb, report_path, render_path = args[0], args[1], args[2]
    size, samples = int(args[3]), int(args[4])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.object.volume_import(filepath=vdb)
    obj = bpy.context.active_object
    obj.data.grids.load()
    box = [list(c) for c in obj.bound_box]
    lo = [min(c[i] for c in box) for i in range(3)]
    hi = [max(c[i] for c in box) for i in range(3)]
    report = {"grids": {g.name: g.data_type for g in obj.data.grids}, "min": lo, "max": hi}

    material = bpy.data.materials.new("stone")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    for n in list(nodes):
        if n.type != "OUTPUT_MATERIAL":
            nodes.remove(n)
    volume = nodes.new("ShaderNodeVolumePrincipled")
    volume.inputs["Density"].default_value = 1.0  # the grid is the extinction already
    colour = nodes.new("ShaderNodeAttribute")
    colour.attribute_name = "color"
    links.new(colour.outputs["Color"], volume.inputs["Color"])
    output = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    links.new(volume.outputs["Volume"], output.inputs["Volume"])
    obj.data.materials.append(material)

    scene = bpy.context.scene
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    extent = max(b - a for a, b in zip(lo, hi))
    blender_render.ortho_camera(scene, (centre[0], centre[1] - 3.0 * extent, centre[2]),
                                1.5 * extent)
    sun_data = bpy.data.lights.new("sun", "SUN")
    sun_data.energy = 3.0
    sun = bpy.data.objects.new("sun", sun_data)
    sun.rotation_euler = (0.8, 0.2, 0.3)
    scene.collection.objects.link(sun)
    blender_render.world(scene, 0.0)
    blender_render.render_exr(scene, render_path, size, samples)
    with open(report_path, "w") as f:
        json.dump(report, f, indent=1)


main()
