"""Screenshots of Blender's real UI with the add-on, for docs/blender.md.

    docs/img/blender_screenshots.sh [BUILD] [OUTDIR]   (runs this twice)

First in background mode ("prepare"): installs build/shafts_blender.zip into
a scratch user scripts folder (Preferences > Add-ons > Install, as a user
does) and saves the engines' test scene (a spot and a caster in a volume
box, blender_addon/tests/scenes.py) as a .blend. Then with a window under
xvfb ("shoot"), opening that file (so no splash screen): for each engine,
the 3D viewport in Rendered shading through the camera with the engine's
settings in the Properties editor (for the sweep, after moving the spot),
then F12 with the render shown in the main window. Each screenshot is the
whole window (bpy.ops.screen.screenshot), scaled to 75% by the shell
script: OUTDIR/blender_<engine>_<viewport|render>.png.
"""
import os
import sys
import time
from pathlib import Path

import addon_utils
import bpy

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
ARGS = sys.argv[sys.argv.index("--") + 1:]
VIEWPORT_WAIT = {"SHAFTS_SWEEP": 6.0, "SHAFTS_TRACER": 30.0}


def log(text):
    print("blender_screenshots: " + text, flush=True)


def prepare(blend):
    sys.path.insert(0, str(ROOT / "blender_addon" / "tests"))
    bpy.ops.preferences.addon_install(filepath=os.environ["SHAFTS_ADDON_ZIP"])
    addon_utils.enable("shafts_blender", default_set=True)
    import scenes
    scene = scenes.spot_in_volume_box()
    scene.render.resolution_x, scene.render.resolution_y = 640, 480
    scene.view_settings.view_transform = "Standard"
    scene.shafts_tracer.spp = 16
    scene.shafts_tracer.viewport_spp = 8
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    log("saved %s" % blend)


def area_of(window, kind):
    return next(a for a in window.screen.areas if a.type == kind)


def screenshot(window, out, name):
    path = Path(out) / ("blender_%s.png" % name)
    with bpy.context.temp_override(window=window, screen=window.screen):
        bpy.ops.screen.screenshot(filepath=str(path))
    log("wrote %s" % path)


def shoot(out):
    """A generator: each yield waits that many seconds with Blender's UI
    running (bpy.app.timers)."""
    addon_utils.enable("shafts_blender", default_set=True)
    bpy.context.preferences.view.render_display_type = 'SCREEN'
    yield 1.0
    scene = bpy.context.scene
    window = bpy.context.window_manager.windows[0]
    view = area_of(window, "VIEW_3D")
    space = view.spaces.active
    space.region_3d.view_perspective = 'CAMERA'
    space.overlay.show_overlays = True  # the engine's stats line
    space.overlay.show_cursor = False
    props = area_of(window, "PROPERTIES").spaces.active
    for engine, short in (("SHAFTS_SWEEP", "sweep"), ("SHAFTS_TRACER", "tracer")):
        scene.render.engine = engine
        props.context = 'RENDER'
        space.shading.type = 'RENDERED'
        log("%s in the viewport" % engine)
        yield VIEWPORT_WAIT[engine]
        if engine == "SHAFTS_SWEEP":
            # A light move: the header then shows the frame it took and
            # that it compiled no program.
            bpy.data.objects["Spot"].location.x += 0.3
            yield 3.0
        screenshot(window, out, short + "_viewport")
        space.shading.type = 'SOLID'
        with bpy.context.temp_override(window=window):
            bpy.ops.render.render('INVOKE_DEFAULT')
        start = time.monotonic()
        yield 2.0
        while bpy.app.is_job_running('RENDER') and time.monotonic() - start < 300:
            yield 1.0
        yield 1.0
        window = bpy.context.window_manager.windows[0]
        screenshot(window, out, short + "_render")
        image = area_of(window, "IMAGE_EDITOR")
        with bpy.context.temp_override(window=window, area=image):
            bpy.ops.render.view_cancel()
        yield 1.0
        window = bpy.context.window_manager.windows[0]
        view = area_of(window, "VIEW_3D")
        space = view.spaces.active
    bpy.ops.wm.quit_blender()


def run(generator):
    def tick():
        try:
            return next(generator)
        except StopIteration:
            return None
        except Exception as e:
            log("failed: %s: %s" % (type(e).__name__, e))
            os._exit(1)
    bpy.app.timers.register(tick, first_interval=2.0)


if ARGS[0] == "prepare":
    prepare(ARGS[1])
else:
    run(shoot(ARGS[1]))
