"""Bad input in Blender: what the scene format cannot hold renders
approximated with each approximation reported as a warning; a render the
library refuses ends with an error report and writes no image (never a
black one); a cancelled render returns promptly, writes nothing and leaves
the add-on able to render again."""
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import addon_test_lib as t  # noqa: E402

t.install()
t.require("shafts", "convert")
import bpy  # noqa: E402
from scenes import spot_in_volume_box  # noqa: E402
from shafts_blender import convert, final  # noqa: E402
from artist_scene import add_object, light, plane_mesh  # noqa: E402

out = t.SCRATCH

# Unsupported lights and nodes: an area light, a surface with an image
# texture and a Glass BSDF.
scene = spot_in_volume_box()
scene.render.engine = "SHAFTS_SWEEP"
light(scene, "Panel", "AREA", 200.0, (2, -1, 3), size=0.5)
card = add_object(scene, "Card", plane_mesh("Card", 1.0), (1.5, 0, 0.5), (90, 0, 0))
mat = bpy.data.materials.new("Textured")
mat.use_nodes = True
nodes = mat.node_tree.nodes
image = nodes.new("ShaderNodeTexImage")
image.image = bpy.data.images.new("checker", 8, 8)
image.image.generated_type = "COLOR_GRID"
mat.node_tree.links.new(image.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
card.data.materials.append(mat)
exported = convert.export_scene(bpy.context.evaluated_depsgraph_get(), size=(64, 48))
warnings = exported.warnings
t.check(any("Panel" in w for w in warnings), "the area light is named in a warning")
t.check(any("Textured" in w for w in warnings), "the image texture's material is named in a warning")
with t.captured_stdout() as printed:
    result = t.f12(scene, out / "approximated.exr")
t.check(result == {'FINISHED'} and (out / "approximated.exr").is_file(),
        "the approximated scene renders")
missing = [w for w in warnings if w not in printed.text]
t.check(not missing, "every warning is reported in Blender (%d warnings; missing: %s)"
        % (len(warnings), missing))

# A render the library refuses: the refined variant needs the refract-both
# scheme.
scene = spot_in_volume_box()
scene.render.engine = "SHAFTS_TRACER"
settings = scene.shafts_tracer
settings.mode, settings.scheme, settings.refined, settings.spp = 'LMM', 'STRAIGHT', True, 1
result = t.f12(scene, out / "refused.exr")
t.check("Shafts: rendering failed" in str(result), "the library's error is reported: %s" % result)
t.check(not (out / "refused.exr").exists(), "no image written after the error (F12: %s)" % result)


# Cancel: Blender's Esc cannot be pressed in background mode, so a stand-in
# for the RenderEngine's calls asks for a break 0.3 s into a long render.
class Breaking:
    def __init__(self, after):
        self.after, self.start = after, time.perf_counter()
        self.reports, self.errors, self.results = [], [], 0

    def test_break(self):
        return time.perf_counter() - self.start > self.after

    def report(self, kind, text):
        self.reports.append((kind, text))

    def error_set(self, text):
        self.errors.append(text)

    def begin_result(self, *args):
        self.results += 1
        raise AssertionError("a cancelled render must not write a result")

    def update_stats(self, *args):
        pass

    def update_progress(self, value):
        pass


# The library checks its cancel flag between 16x16 tiles: 192 tiles of
# 1000 samples here, about a minute of work on 2 cores.
scene = spot_in_volume_box()
scene.render.resolution_x, scene.render.resolution_y = 256, 192
settings = scene.shafts_tracer
settings.spp = 1000
threads = threading.active_count()
engine = Breaking(0.3)
start = time.perf_counter()
final.render(engine, bpy.context.evaluated_depsgraph_get(), "tracer")
took = time.perf_counter() - start
t.check(took < 3.0, "the cancelled render returned after %.2f s" % took)
t.check(engine.results == 0 and not engine.errors
        and not [r for r in engine.reports if 'ERROR' in r[0]],
        "a cancel writes no result and reports no error")
t.check(threading.active_count() == threads, "no thread left running")
# Progress: the same stand-in, never breaking, records what F12 reports
# while the tracer renders 12 tiles (about a second); its result goes to a recording pass.
class Recording(Breaking):
    def __init__(self):
        super().__init__(after=1e9)
        self.progress, self.pixels = [], None

    def update_progress(self, value):
        self.progress.append(value)

    def begin_result(self, x, y, w, h):
        engine = self

        class Pass:
            class rect:
                @staticmethod
                def foreach_set(values):
                    engine.pixels = values.copy()

        class Layer:
            passes = {"Combined": Pass}

        class Result:
            layers = [Layer]
        self.results += 1
        return Result

    def end_result(self, result, cancel=False):
        pass


settings.spp = 1024
scene.render.resolution_x, scene.render.resolution_y = 64, 48
engine = Recording()
final.render(engine, bpy.context.evaluated_depsgraph_get(), "tracer")
steps = engine.progress
t.check(not engine.errors and engine.results == 1 and engine.pixels is not None
        and engine.pixels.shape == (64 * 48, 4), "the stand-in got one 64x48 RGBA result")
t.check(len(steps) >= 2 and steps == sorted(steps) and steps[-1] == 1.0
        and any(0 < v < 1 for v in steps),
        "progress is reported while rendering, rising to 1 (%d reports: %s)"
        % (len(steps), sorted(set(round(v, 2) for v in steps))))
settings.spp = 2
scene.render.engine = "SHAFTS_TRACER"
result = t.f12(scene, out / "after_cancel.exr")
t.check(result == {'FINISHED'} and (out / "after_cancel.exr").is_file(),
        "F12 renders after the cancel")
t.finish()
