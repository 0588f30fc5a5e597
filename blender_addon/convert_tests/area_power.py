"""Measures the radiant intensity of Cycles' lights per watt, the figure
light.py's AREA_INTENSITY_PER_WATT and docs/blender.md (Mapping) quote:

    blender -b --factory-startup --python area_power.py

A 100 W light (a 5 cm square area light, a point light, a 60-degree spot,
radius 0) 2 m above a white Diffuse BSDF floor; the camera looks at the
point under it, so the floor's radiance L = E / pi = I / (pi d^2) gives
I = pi d^2 L = 4 pi L. Prints I for each light (point and spot: P / (4 pi) =
7.958)."""
import math

import bpy
import numpy as np

WATTS, HEIGHT = 100.0, 2.0


def measure(kind):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    me = bpy.data.meshes.new("floor")
    me.from_pydata([(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [], [(0, 1, 2, 3)])
    mat = bpy.data.materials.new("white")
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (1, 1, 1, 1)
    tree.links.new(diffuse.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    me.materials.append(mat)
    scene.collection.objects.link(bpy.data.objects.new("floor", me))
    light = bpy.data.lights.new("light", kind)
    light.energy = WATTS
    if kind == "AREA":
        light.size = 0.05
    else:
        light.shadow_soft_size = 0.0
    if kind == "SPOT":
        light.spot_size, light.spot_blend = math.radians(60), 0.0
    obj = bpy.data.objects.new("light", light)
    obj.location = (0, 0, HEIGHT)
    scene.collection.objects.link(obj)
    cam = bpy.data.cameras.new("camera")
    cam.angle = math.radians(2)
    cam_obj = bpy.data.objects.new("camera", cam)
    cam_obj.location = (0, 0, 1.5)
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj
    scene.world = bpy.data.worlds.new("black")
    scene.world.color = (0, 0, 0)
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 64
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = 8
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = bpy.app.tempdir + "area_power_%s.exr" % kind
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(scene.render.filepath)
    px = np.empty(len(img.pixels), dtype=np.float32)
    img.pixels.foreach_get(px)
    radiance = float(px.reshape(-1, 4)[:, :3].mean())
    return math.pi * HEIGHT ** 2 * radiance


for kind in ("AREA", "POINT", "SPOT"):
    i = measure(kind)
    print("%-5s %g W: axial intensity %.4g W/sr = %.4f P" % (kind, WATTS, i, i / WATTS))
