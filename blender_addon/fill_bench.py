"""How long filling Blender's render result takes, 1920x1080 by default.

    blender -b --factory-startup --python blender_addon/fill_bench.py [-- W H RUNS]

Registers a bare engine whose render() fills the result with the add-on's
result.fill (no library involved) and prints the median of RUNS renders of:
the RGB -> RGBA bottom-up copy, begin_result + foreach_set, end_result
(Blender's own merge of the result), and their sum. The issue's target: the
fill under 50 ms at 1920x1080.
"""
import statistics
import sys
import time
from pathlib import Path

import bpy
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from shafts_blender import result  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
W, H, RUNS = (int(v) for v in (argv + ["1920", "1080", "9"][len(argv):]))
times = {"copy": [], "foreach_set": [], "end_result": [], "fill": []}


class FillBenchEngine(bpy.types.RenderEngine):
    bl_idname = "SHAFTS_FILL_BENCH"
    bl_label = "fill bench"

    def render(self, depsgraph):
        rgb = np.random.default_rng(len(times["fill"])).random((H, W, 3), dtype=np.float32)
        t0 = time.perf_counter()
        pixels = result.rgba_bottom_up(rgb, result._fill_cache)
        t1 = time.perf_counter()
        res = self.begin_result(0, 0, W, H)
        res.layers[0].passes["Combined"].rect.foreach_set(pixels)
        t2 = time.perf_counter()
        self.end_result(res)
        t3 = time.perf_counter()
        result.fill(self, rgb)
        t4 = time.perf_counter()
        times["copy"].append(t1 - t0)
        times["foreach_set"].append(t2 - t1)
        times["end_result"].append(t3 - t2)
        times["fill"].append(t4 - t3)


bpy.utils.register_class(FillBenchEngine)
scene = bpy.context.scene
scene.render.engine = FillBenchEngine.bl_idname
scene.render.resolution_x, scene.render.resolution_y = W, H
scene.render.resolution_percentage = 100
for _ in range(RUNS):
    bpy.ops.render.render()
print("fill_bench: %dx%d, median of %d renders (ms):" % (W, H, RUNS))
for name, values in times.items():
    print("  %-12s %7.1f" % (name, 1000 * statistics.median(values)))
print("  result.fill = copy + begin_result + foreach_set + end_result")
