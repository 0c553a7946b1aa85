# What the Blender checks share: an orthographic camera and Cycles settings that give
# scene-linear Rec.709 values a test can compare (the Standard view, no denoising, a fixed
# seed), written to an EXR.
import bpy


def ortho_camera(scene, location, scale):
    """An orthographic camera at `location` looking along +Y, `scale` wide."""
    data = bpy.data.cameras.new("camera")
    data.type = "ORTHO"
    data.ortho_scale = scale
    camera = bpy.data.objects.new("camera", data)
    camera.location = location
    camera.rotation_euler = (1.5707963267948966, 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera


def world(scene, strength):
    """A uniform white world of `strength` (0: black)."""
    w = bpy.data.worlds.new("world")
    w.use_nodes = True
    background = w.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    background.inputs["Strength"].default_value = strength
    scene.world = w


def render_exr(scene, path, size, samples):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.seed = 1
    scene.render.resolution_x = size
    scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
