# Blender's Nishita sky texture, rendered by Cycles for validation/nishita.py
# and tools/bench_sky.py. Run inside Blender 3.4:
#
#   blender -b --factory-startup -P validation/nishita_blender.py -- JOB.json
#
# JOB.json is data (never code): {"out": DIR, "views": [VIEW, ...]} with each
# VIEW {"name": str, "elevation_deg": number, "dir": [x, y, z] (the camera's
# viewing direction in Blender's Z-up frame), "fov_deg": number (vertical),
# "width": int, "height": int, "samples": int, and optionally "air", "dust",
# "ozone" (the densities, default 1), "sun_disc" (default true),
# "sun_size_deg" (default Blender's 0.545), "altitude_m" (default 0)}. The
# world is a Sky Texture of type NISHITA (sun rotation 0: the sun towards +Y) into a
# Background of strength 1; nothing else is in the scene, so each pixel is
# the texture's value in the direction of its camera ray. Each view is
# rendered to DIR/NAME.exr (32-bit float, scene linear); DIR/results.json
# gets, per view, the middle pixel's RGB (the ray along "dir" when width
# and height are odd) and the render's wall time in seconds.
import json
import math
import sys
import time

import bpy


def _job():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        print("nishita_blender: usage: blender -b --factory-startup -P "
              "nishita_blender.py -- JOB.json", file=sys.stderr)
        sys.exit(2)
    with open(argv[0]) as f:
        return json.load(f)


def _scene():
    """An empty scene with the Nishita world and a camera."""
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    # A box filter a hundredth of a pixel wide: every sample is the pixel's
    # centre ray to within 0.005 pixels.
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 0.01
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    world = bpy.data.worlds.new("nishita")
    world.use_nodes = True
    nodes = world.node_tree.nodes
    sky = nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    sky.altitude = 0.0
    sky.sun_rotation = 0.0
    background = nodes["Background"]
    background.inputs["Strength"].default_value = 1.0
    world.node_tree.links.new(sky.outputs["Color"], background.inputs["Color"])
    scene.world = world
    cam = bpy.data.cameras.new("camera")
    cam.lens_unit = "FOV"
    cam.sensor_fit = "VERTICAL"
    cam.clip_start = 1e-3
    obj = bpy.data.objects.new("camera", cam)
    scene.collection.objects.link(obj)
    scene.camera = obj
    return scene, sky, obj


def _middle(path, width, height):
    img = bpy.data.images.load(path)
    px = img.pixels[:]
    i = 4 * ((height // 2) * width + width // 2)
    rgb = [px[i], px[i + 1], px[i + 2]]
    bpy.data.images.remove(img)
    return rgb


def main():
    job = _job()
    scene, sky, cam = _scene()
    results = {"blender": bpy.app.version_string, "views": {}}
    from mathutils import Vector
    for view in job["views"]:
        sky.sun_elevation = math.radians(view["elevation_deg"])
        sky.altitude = float(view.get("altitude_m", 0.0))
        sky.air_density = float(view.get("air", 1.0))
        sky.dust_density = float(view.get("dust", 1.0))
        sky.ozone_density = float(view.get("ozone", 1.0))
        sky.sun_disc = bool(view.get("sun_disc", True))
        sky.sun_size = math.radians(view.get("sun_size_deg", 0.545))
        scene.cycles.samples = int(view.get("samples", 1))
        scene.render.resolution_x = int(view["width"])
        scene.render.resolution_y = int(view["height"])
        cam.data.angle_y = math.radians(view["fov_deg"])
        d = Vector(view["dir"]).normalized()
        cam.rotation_mode = "QUATERNION"
        cam.rotation_quaternion = d.to_track_quat("-Z", "Y")
        path = "%s/%s.exr" % (job["out"], view["name"])
        scene.render.filepath = path
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        seconds = time.perf_counter() - t0
        results["views"][view["name"]] = {
            "rgb": _middle(path, view["width"], view["height"]),
            "seconds": seconds}
        print("nishita_blender: %s %.3f s" % (view["name"], seconds))
    with open("%s/results.json" % job["out"], "w") as f:
        json.dump(results, f, indent=1)


main()
