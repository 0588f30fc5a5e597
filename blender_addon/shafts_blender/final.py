"""F12: one frame of either engine into Blender's render result.

The scene is converted in memory (convert.export_scene), built by the
library (shafts.Scene.from_json), rendered on a worker thread while the
render thread polls test_break and reports progress, then written into the
render result in one foreach_set. Every failure becomes an ERROR report and
error_set, and no result is written: Blender then marks the render as
failed instead of showing or saving a black image.
"""
import time

from . import job as jobmod
from .errors import describe, is_cancelled
from .properties import sweep_options, tracer_arguments


def render_size(scene):
    r = scene.render
    scale = r.resolution_percentage / 100.0
    return max(1, int(r.resolution_x * scale)), max(1, int(r.resolution_y * scale))


def export(engine, depsgraph, size, view=None):
    """convert.export_scene with each warning reported; the Export."""
    from . import convert
    exported = convert.export_scene(depsgraph, view=view, size=size)
    for warning in exported.warnings:
        engine.report({'WARNING'}, warning)
    return exported


def build_scene(exported):
    from . import shafts
    return shafts.Scene.from_json(exported.text, name="blender.json", base_dir=".",
                                  meshes=exported.meshes)


def fail(engine, what, error):
    text = "Shafts: %s failed: %s" % (what, describe(error))
    engine.report({'ERROR'}, text)
    engine.error_set(text)


def render(engine, depsgraph, kind):
    """The body of RenderEngine.render for kind "sweep" or "tracer"."""
    scene = depsgraph.scene
    size = render_size(scene)
    engine.update_stats("", "Shafts: converting the scene")
    try:
        from . import shafts  # loads libshafts.so: its failure is reported too
        exported = export(engine, depsgraph, size)
        sh_scene = build_scene(exported)
    except Exception as e:
        fail(engine, "preparing the scene", e)
        return
    try:
        progress = jobmod.Progress()
        cancel = shafts.CancelFlag()
        if kind == "sweep":
            options = sweep_options(scene.shafts_sweep)

            def work():
                renderer = shafts.SweepRenderer(sh_scene, options=options)
                try:
                    return renderer.draw()
                finally:
                    renderer.close()
        else:
            name, arguments = tracer_arguments(scene.shafts_tracer)
            fn = getattr(shafts, name)

            def work():
                return fn(sh_scene, progress=progress, cancel=cancel, **arguments)

        engine.update_stats("", "Shafts: rendering")
        running = jobmod.Job(work).start()
        started = time.perf_counter()

        def tick():
            engine.update_progress(progress.fraction())
            engine.update_stats("", "Shafts: rendering, %.1f s" % (time.perf_counter() - started))

        broke = running.watch(engine.test_break, cancel, tick)
        if running.error is not None:
            if is_cancelled(running.error) or broke:
                engine.update_stats("", "Shafts: cancelled")
                return
            fail(engine, "rendering", running.error)
            return
        if broke:
            return
        rgb, stats = running.result
        from . import result
        result.fill(engine, rgb)
        engine.update_progress(1.0)
        if kind != "sweep":
            stats = dict(stats or {}, spp=arguments["spp"])
        engine.update_stats("", summary(kind, stats, running.seconds))
    except Exception as e:
        fail(engine, "rendering", e)
    finally:
        sh_scene.close()


def summary(kind, stats, seconds):
    """The stats line: planes or samples, and time."""
    stats = stats or {}
    if kind == "sweep":
        return "Shafts sweep | planes %s | %.3f s" % (stats.get("planes", "?"), seconds)
    return "Shafts tracer | spp %s | %.2f s" % (stats.get("spp", "?"), seconds)
