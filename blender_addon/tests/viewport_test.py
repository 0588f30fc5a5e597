"""The sweep's viewport path, driven as view_update and view_draw drive it
but without a window (background mode): the ViewportWorker's thread owns a
live renderer; after a camera move, a light move and dimming, and a change
of the medium, each frame compiles no program (the renderer's stats) and
equals a fresh renderer of the same scene (bit for bit for a fresh live
renderer; within float rounding for F12's non-live one, whose values are
compiled in as constants). A 3D view's matrices give the camera's image."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import addon_test_lib as t  # noqa: E402

t.install()
t.require("shafts", "convert")
import bpy  # noqa: E402
import numpy as np  # noqa: E402
from scenes import spot_in_volume_box  # noqa: E402
from shafts_blender import convert, shafts  # noqa: E402
from shafts_blender.properties import sweep_options  # noqa: E402
from shafts_blender.viewport import SweepWorker  # noqa: E402

# Live (uniforms) against non-live (constants folded by the compiler):
# relative RMS over the image.
NON_LIVE_MAX_REL_RMS = 1e-5
SIZE = (64, 48)


def rel_rms(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)) / max(np.sqrt(np.mean(b ** 2)), 1e-30))


def wait_idle(worker, timeout=60.0):
    """Until a worker has nothing queued or left to refine."""
    import time
    deadline = time.monotonic() + timeout
    while not worker.idle() and time.monotonic() < deadline:
        time.sleep(0.02)


def fresh(exported, options, live):
    scene = shafts.Scene.from_json(exported.text, meshes=exported.meshes)
    try:
        renderer = shafts.SweepRenderer(scene, options=options, live=live)
        try:
            return renderer.draw()[0]
        finally:
            renderer.close()
    finally:
        scene.close()


scene = spot_in_volume_box()
options = sweep_options(scene.shafts_sweep)
frames = []
worker = SweepWorker(options=options, on_frame=lambda: frames.append(1))
try:
    depsgraph = bpy.context.evaluated_depsgraph_get()
    exported = convert.export_scene(depsgraph, size=SIZE)
    worker.rebuild(exported)
    frame = worker.wait_frame(0)
    t.check(frame is not None and worker.error is None,
            "first frame (%s)" % (worker.error or "%.0f ms" % (1000 * frame.seconds)))
    t.check(frames == [1], "on_frame called once per frame")
    t.check(np.array_equal(frame.rgb, fresh(exported, options, True)),
            "the first frame equals a fresh live renderer's")

    light, fog = bpy.data.objects["Spot"], bpy.data.materials["Fog"]

    def move_camera():
        scene.camera.location.x += 0.3
        scene.camera.location.z -= 0.2

    def move_light():
        light.location.z -= 0.2
        light.data.energy *= 0.99

    def densify():
        fog.node_tree.nodes["Principled Volume"].inputs["Density"].default_value = 0.25

    moves = {"camera move": move_camera, "light move and 1% dimmer": move_light,
             "denser medium": densify}
    for what, change in moves.items():
        change()
        depsgraph = bpy.context.evaluated_depsgraph_get()
        depsgraph.update()
        patch = convert.export_patch(depsgraph, exported, size=SIZE)
        t.check(patch is not None, "%s: a patch, no rebuild" % what)
        if patch is None:
            continue
        worker.patch(patch)
        frame = worker.wait_frame(frame.number)
        if not t.check(frame is not None and worker.error is None,
                       "%s: a new frame%s" % (what, ": " + worker.error if worker.error else "")):
            break
        compiled = frame.stats.get("programs_compiled")
        t.check(compiled == 0, "%s: no program compiled (%s), %.0f ms"
                % (what, compiled, 1000 * frame.seconds))
        now = convert.export_scene(depsgraph, size=SIZE)
        t.check(np.array_equal(frame.rgb, fresh(now, options, True)),
                "%s: equals a fresh live renderer's frame bit for bit" % what)
        e = rel_rms(frame.rgb, fresh(now, options, False))
        t.check(e <= NON_LIVE_MAX_REL_RMS, "%s: equals F12's renderer within %g (%g)"
                % (what, NON_LIVE_MAX_REL_RMS, e))

    # A viewport resized: the patch carries the new size.
    depsgraph = bpy.context.evaluated_depsgraph_get()
    bigger = (80, 60)
    worker.patch(convert.export_patch(depsgraph, exported, size=bigger))
    frame = worker.wait_frame(frame.number)
    if t.check(frame is not None and frame.rgb.shape == (60, 80, 3),
               "a resized view draws at its new size (%s)"
               % ((frame.rgb.shape,) if frame else worker.error)):
        t.check(frame.stats.get("programs_compiled") == 0, "a resize compiles no program")
        t.check(np.array_equal(frame.rgb, fresh(convert.export_scene(depsgraph, size=bigger),
                                                options, True)),
                "the resized frame equals a fresh live renderer's")

    # The view of a 3D viewport looking through the camera gives its image.
    depsgraph = bpy.context.evaluated_depsgraph_get()
    cam = scene.camera
    view = (cam.matrix_world.inverted(), cam.calc_matrix_camera(depsgraph, x=SIZE[0], y=SIZE[1]))
    a = convert.export_scene(depsgraph, size=SIZE)
    b = convert.export_scene(depsgraph, view=view, size=SIZE)
    e = rel_rms(fresh(b, options, True), fresh(a, options, True))
    t.check(e <= NON_LIVE_MAX_REL_RMS, "a 3D view through the camera renders the camera's "
            "image (rel RMS %g)" % e)
finally:
    worker.close()
t.check(worker._scene is None and worker._renderer is None, "close frees the renderer")

# The tracer's viewport refines: 1, 2, then 4 samples per pixel, the last
# equal to a render at 4 (the reference is deterministic for a seed); a
# change starts again from 1 sample.
from shafts_blender.engine import spp_steps  # noqa: E402
from shafts_blender.properties import tracer_arguments  # noqa: E402
from shafts_blender.viewport import TracerWorker  # noqa: E402

name, arguments = tracer_arguments(scene.shafts_tracer)
spps = []
worker = TracerWorker(name, arguments, spp_steps(4), on_frame=lambda: spps.append(worker.frame.stats["spp"]))
try:
    depsgraph = bpy.context.evaluated_depsgraph_get()
    exported = convert.export_scene(depsgraph, size=SIZE)
    worker.rebuild(exported)
    wait_idle(worker)
    t.check(spps == [1, 2, 4], "the tracer refines with 1, 2, 4 samples per pixel: %s" % spps)
    s = shafts.Scene.from_json(exported.text, meshes=exported.meshes)
    want = getattr(shafts, name)(s, **dict(arguments, spp=4))[0]
    s.close()
    t.check(np.array_equal(worker.frame.rgb, want), "its last frame equals a render at 4 spp")
    spps.clear()
    scene.camera.location.x -= 0.3
    depsgraph = bpy.context.evaluated_depsgraph_get()
    worker.patch(convert.export_patch(depsgraph, exported, size=SIZE))
    wait_idle(worker)
    t.check(spps[:1] == [1], "a camera move starts again from 1 sample: %s" % spps)
finally:
    worker.close()
t.finish()
