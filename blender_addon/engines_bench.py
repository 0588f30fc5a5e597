"""What the engines' steps cost in Blender, on the tests' spot-in-a-volume-box
scene at 640x480 (the add-on installed from build/shafts_blender.zip):

    blender_addon/engines_bench.sh [BUILD]      (runs this in background mode)

F12 of each engine (the render operator as a whole, and its parts: the
conversion, building the scene in the library, rendering), then the sweep's
viewport worker (a live renderer on its thread): the first frame, and
frames after a camera move and after a light move, each the median of RUNS,
with the programs compiled for them. Prints a table; docs/blender.md quotes
it.
"""
import os
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "tests"))
import addon_test_lib as t  # noqa: E402

t.install()
t.require("shafts", "convert")
import bpy  # noqa: E402
from scenes import spot_in_volume_box  # noqa: E402
from shafts_blender import convert, shafts  # noqa: E402
from shafts_blender.properties import sweep_options, tracer_arguments  # noqa: E402
from shafts_blender.viewport import SweepWorker  # noqa: E402

SIZE, RUNS = (640, 480), 5


def ms(seconds):
    return "%8.1f" % (1000 * seconds)


def timed(fn):
    start = time.perf_counter()
    value = fn()
    return value, time.perf_counter() - start


scene = spot_in_volume_box()
scene.render.resolution_x, scene.render.resolution_y = SIZE
rows = ["engines_bench: %dx%d, Blender %s, %d runs per median, load average %.1f"
        % (SIZE + (bpy.app.version_string, RUNS, os.getloadavg()[0])),
        "%-44s %8s" % ("step", "ms")]


def row(text):
    rows.append(text)


depsgraph = bpy.context.evaluated_depsgraph_get()
exported, took = timed(lambda: convert.export_scene(depsgraph, size=SIZE))
row("%-44s %s" % ("convert.export_scene", ms(took)))
built, took = timed(lambda: shafts.Scene.from_json(exported.text, meshes=exported.meshes))
row("%-44s %s" % ("Scene.from_json", ms(took)))


def sweep():
    renderer = shafts.SweepRenderer(built, options=sweep_options(scene.shafts_sweep))
    try:
        return renderer.draw()
    finally:
        renderer.close()


_, took = timed(sweep)
row("%-44s %s" % ("SweepRenderer: create, draw, close", ms(took)))
name, arguments = tracer_arguments(scene.shafts_tracer)
_, took = timed(lambda: getattr(shafts, name)(built, **arguments))
row("%-44s %s" % ("%s, %d spp" % (name, arguments["spp"]), ms(took)))
built.close()
for engine in ("SHAFTS_SWEEP", "SHAFTS_TRACER"):
    scene.render.engine = engine
    _, took = timed(lambda: bpy.ops.render.render())
    row("%-44s %s" % ("F12 %s (the operator)" % engine, ms(took)))

worker = SweepWorker(options=sweep_options(scene.shafts_sweep))
try:
    worker.rebuild(exported)
    frame = worker.wait_frame(0)
    row("%-44s %s  (programs compiled: %s)" % ("viewport: first frame (scene + renderer)",
                                                 ms(frame.seconds),
                                                 frame.stats.get("programs_compiled")))
    light = bpy.data.objects["Spot"]

    def camera(i):
        scene.camera.location.x += 0.05 * (1 if i % 2 else -1)

    def lamp(i):
        light.location.z += 0.05 * (1 if i % 2 else -1)
        light.data.energy *= 1.01

    for what, move in (("camera move", camera), ("light move and 1% brighter", lamp)):
        times, compiled = [], []
        for i in range(RUNS):
            move(i)
            depsgraph = bpy.context.evaluated_depsgraph_get()
            patch, took_patch = timed(lambda: convert.export_patch(depsgraph, exported, size=SIZE))
            worker.patch(patch)
            frame = worker.wait_frame(frame.number)
            times.append((took_patch, frame.seconds))
            compiled.append(frame.stats.get("programs_compiled"))
        patch_s = statistics.median(p for p, _ in times)
        frame_s = statistics.median(f for _, f in times)
        row("%-44s %s  (export_patch %s ms; programs compiled: %s)"
              % ("viewport: frame after a " + what, ms(frame_s), ms(patch_s).strip(),
                 sorted(set(compiled))))
finally:
    worker.close()
print("\n".join(rows))
sys.exit(0)
