# One rendering by the Blender add-on's engines, for the validation.
#
#   blender -b --factory-startup --python-exit-code 1 \
#     --python validation/blender_addon_render.py -- \
#     ADDON.zip SCENE.json OUT.exr SHAFTS_SWEEP|SHAFTS_TRACER SETTINGS.json
#
# With BLENDER_USER_SCRIPTS set to an empty scratch directory, as a user's
# fresh Blender: it unpacks the zip into the user add-ons folder, enables
# shafts_blender, imports the scene as File > Import > Shafts scene does
# (the add-on's importer: the objects Cycles renders), sets the engine and
# its settings (SETTINGS.json: attributes of scene.shafts_sweep or
# scene.shafts_tracer, JSON numbers and strings only) and renders F12 into
# a 32-bit linear EXR, the way a user would. It prints the render's time
# as "shafts_addon_render_seconds: S" (F12 alone, import excluded).
import json
import sys
import time
import zipfile

import addon_utils
import bpy

ENGINES = {"SHAFTS_SWEEP": "shafts_sweep", "SHAFTS_TRACER": "shafts_tracer"}


def fail(message):
    print("blender_addon_render: " + message, file=sys.stderr, flush=True)
    sys.exit(2)


def main(argv):
    if len(argv) != 5 or argv[3] not in ENGINES:
        fail("usage: -- ADDON.zip SCENE.json OUT.exr SHAFTS_SWEEP|SHAFTS_TRACER SETTINGS.json")
    addon_zip, scene_path, out, engine, settings_path = argv
    with zipfile.ZipFile(addon_zip) as z:
        z.extractall(bpy.utils.user_resource('SCRIPTS', path="addons"))
    addon_utils.modules_refresh()
    if addon_utils.enable("shafts_blender", default_set=True) is None:
        fail("cannot enable the add-on shafts_blender")
    from shafts_blender.convert import importer

    scene = bpy.context.scene
    for obj in list(scene.objects):
        bpy.data.objects.remove(obj)
    try:
        importer.import_scene(bpy.context, scene_path)
    except importer.ImportFailed as e:
        fail("import failed: %s" % e)

    scene.render.engine = engine
    group = getattr(scene, ENGINES[engine])
    with open(settings_path) as f:
        settings = json.load(f)
    for key, value in settings.items():
        if not isinstance(value, (int, float, str)) or not hasattr(group, key):
            fail("bad setting %r" % key)
        setattr(group, key, value)

    render = scene.render
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    render.image_settings.color_mode = "RGB"
    render.use_file_extension = False
    render.use_compositing = False
    render.use_sequencer = False
    render.dither_intensity = 0.0
    scene.view_settings.view_transform = "Standard"
    render.filepath = out
    start = time.perf_counter()
    try:
        result = bpy.ops.render.render(write_still=True)
    except RuntimeError as e:
        fail("F12 failed: %s" % e)
    seconds = time.perf_counter() - start
    if result != {'FINISHED'}:
        fail("F12 returned %s" % result)
    print("shafts_addon_render_seconds: %.6f" % seconds, flush=True)


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
