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
# and two assets lying flat on the ground (Blender's z = 0, facing up):
#   parts.glb, parts_zup_cm.fbx
#                      three 1 m squares side by side along x (x from 0, 1.5 and 3 m), of
#                      the materials Bronze (base colour 0.6 0.4 0.2), Glass (0.9 0.9 0.9) and
#                      Rubber (an 8 x 8 image "tread.png", embedded: in the glb's buffer, in
#                      the FBX's media), each square on its own third of tile 1001 (u from
#                      0, 0.35, 0.70; 0.3 wide). The FBX is Z up in centimetres.
#   two_tiles.glb      two 1 m squares, x from 0 and from 1.5 m, the first on UDIM tile 1001,
#                      the second on tile 1002 (u from 1 to 2)
# The tread is grey 0.2 with a light cross (0.8) on column 3 and row 3 counted from the
# bottom as Blender does (row 4 of the PNG from the top); 8-bit sRGB codes 51 and 204.
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


def squares(name, lefts, uv_lefts, uv_width, units_per_metre, materials):
    """Squares 1 m wide lying on z = 0, the k-th from x = lefts[k], with uvs from
    (uv_lefts[k], 0) to (uv_lefts[k] + uv_width, 1) and material materials[k]."""
    s = units_per_metre
    vertices, faces = [], []
    for k, x in enumerate(lefts):
        vertices += [(x * s, 0, 0), ((x + 1) * s, 0, 0), ((x + 1) * s, s, 0), (x * s, s, 0)]
        faces.append((4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    layer = mesh.uv_layers.new(name="UVMap")
    for k, polygon in enumerate(mesh.polygons):
        u0 = uv_lefts[k]
        corners = [(u0, 0), (u0 + uv_width, 0), (u0 + uv_width, 1), (u0, 1)]
        for corner, loop in zip(corners, polygon.loop_indices):
            layer.data[loop].uv = corner
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    for material in materials:
        mesh.materials.append(material)
    for k, polygon in enumerate(mesh.polygons):
        polygon.material_index = min(k, len(materials) - 1)
    return obj


def tread_image(path):
    """The rubber's texture: 8 x 8, grey 0.2 with a cross of 0.8 on row 3 and column 3."""
    image = bpy.data.images.new("tread", 8, 8)
    pixels = []
    for y in range(8):
        for x in range(8):
            v = 0.8 if x == 3 or y == 3 else 0.2
            pixels += [v, v, v, 1.0]
    image.pixels = pixels
    image.filepath_raw = path
    image.file_format = "PNG"
    image.save()
    return bpy.data.images.load(path)


def principled(name, colour, image=None):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = colour
    if image is not None:
        node = material.node_tree.nodes.new("ShaderNodeTexImage")
        node.image = image
        material.node_tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
    return material


def parts(out, units_per_metre, tread):
    materials = [principled("Bronze", (0.6, 0.4, 0.2, 1.0)),
                 principled("Glass", (0.9, 0.9, 0.9, 1.0)),
                 principled("Rubber", (1.0, 1.0, 1.0, 1.0), tread)]
    return squares("parts", [0.0, 1.5, 3.0], [0.0, 0.35, 0.70], 0.3, units_per_metre, materials)


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

    # The parts, their tread embedded (the PNG written for Blender to load is removed after:
    # only the embedded copies remain).
    tread_file = os.path.join(out, "tread_source.png")
    fresh_scene(1.0)
    parts(out, 1.0, tread_image(tread_file))
    bpy.ops.export_scene.gltf(filepath=os.path.join(out, "parts.glb"))
    fresh_scene(0.01)
    parts(out, 100.0, tread_image(tread_file))
    bpy.ops.export_scene.fbx(filepath=os.path.join(out, "parts_zup_cm.fbx"), axis_up="Z",
                             axis_forward="Y", apply_unit_scale=True, path_mode="COPY",
                             embed_textures=True)
    os.remove(tread_file)

    fresh_scene(1.0)
    squares("two_tiles", [0.0, 1.5], [0.0, 1.0], 1.0, 1.0, [principled("Copper", (1, 1, 1, 1))])
    bpy.ops.export_scene.gltf(filepath=os.path.join(out, "two_tiles.glb"))


main()
