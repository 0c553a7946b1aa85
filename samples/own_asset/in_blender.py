# samples/own_asset: the exported statue as its user first sees it, opened by Blender's own
# glTF importer: each age variant (KHR_materials_variants) displayed in turn and rendered by
# Cycles from the front under a sun and a sky, the ages side by side in one PNG.
#   blender -b --factory-startup --python-exit-code 1 --python in_blender.py -- \
#       STATUE.glb OUT.png SIZE SAMPLES
import math
import os
import sys

import numpy

# Blender 3.4's glTF importer calls numpy.bool, which Debian 12's numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402


def main():
    asset, out, size, samples = sys.argv[sys.argv.index("--") + 1:][:4]
    size, samples = int(size), int(samples)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=asset)
    scene = bpy.context.scene
    obj = next(o for o in bpy.data.objects if o.type == "MESH")
    height = obj.dimensions.z
    if obj.material_slots[0].material is None:
        raise RuntimeError(f"{asset}: the mesh has no material")

    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.lens = 50
    # 50 mm on the 36 mm sensor's long side (the height): 39.6 degrees, 1.3 heights at 1.85.
    camera.location = (0.0, -1.85 * height, 0.48 * height)
    camera.rotation_euler = (math.radians(90), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    bpy.ops.mesh.primitive_plane_add(size=20 * height)  # a grey ground under it
    ground = bpy.context.active_object
    ground.data.materials.append(bpy.data.materials.new("ground"))
    ground.data.materials[0].diffuse_color = (0.35, 0.35, 0.35, 1.0)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(50), 0.0, math.radians(-30))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.8, 0.87, 1.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
    scene.world = world

    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.seed = 1
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    scene.render.resolution_x = size * 3 // 4
    scene.render.resolution_y = size
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"

    variants = [v.name for v in scene.gltf2_KHR_materials_variants_variants]
    frames = []
    for i, name in enumerate(variants):
        scene.gltf2_active_variant = i
        bpy.ops.scene.gltf2_display_variant()
        path = f"{out}.{i}.png"
        scene.render.filepath = path
        bpy.ops.render.render(write_still=True)
        frames.append(numpy.array(bpy.data.images.load(path).pixels[:], dtype=numpy.float32))
        os.remove(path)
        print(f"in_blender: rendered variant '{name}'")

    # The ages side by side, left to right.
    width, rows = scene.render.resolution_x, scene.render.resolution_y
    strip = bpy.data.images.new("strip", width * len(frames), rows)
    pixels = numpy.zeros((rows, width * len(frames), 4), dtype=numpy.float32)
    for k, frame in enumerate(frames):
        pixels[:, k * width:(k + 1) * width, :] = frame.reshape(rows, width, 4)
    strip.pixels = pixels.ravel()
    strip.filepath_raw = out
    strip.file_format = "PNG"
    strip.save()


main()
