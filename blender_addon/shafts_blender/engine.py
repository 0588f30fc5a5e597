"""The two render engines: SHAFTS_SWEEP (gl_shafts' plane sweep) and
SHAFTS_TRACER (lmm_tracer: the reference, Whitted or light meshes).

F12 goes through final.render. In the viewport each engine keeps a worker
(viewport.py) that owns the library's objects on a thread of its own:
view_update and view_draw send it the changes and draw its newest finished
frame as a texture with Blender's gpu module; a timer on Blender's main
thread tags a redraw when the worker has a new frame.
"""
import weakref

import bpy

from . import final
from .errors import describe
from .properties import sweep_options, tracer_arguments

def view_of(context, divider=1):
    """(view_matrix, projection_matrix) and (width, height) of the 3D view
    being drawn, the size divided by ``divider``."""
    region, rv3d = context.region, context.region_data
    size = (max(1, region.width // divider), max(1, region.height // divider))
    return (rv3d.view_matrix.copy(), rv3d.window_matrix.copy()), size


def same_view(a, b):
    if a is None or b is None:
        return False
    (va, pa), sa = a
    (vb, pb), sb = b
    return sa == sb and va == vb and pa == pb


def spp_steps(most):
    """1, 2, 4, ... and then ``most``."""
    steps, spp = [], 1
    while spp < most:
        steps.append(spp)
        spp *= 2
    return steps + [most]


class _RedrawTimer:
    """Polls a worker from Blender's main thread (bpy.app.timers) and tags
    the engine's viewport for a redraw when a newer frame is ready; stops
    when the engine is gone or the worker is idle with its frame drawn."""

    def __init__(self, engine):
        self._engine = weakref.ref(engine)
        self.running = False

    def start(self):
        if not self.running:
            self.running = True
            bpy.app.timers.register(self._tick, first_interval=0.03)

    def _tick(self):
        engine = self._engine()
        try:
            worker = None if engine is None else engine._worker
            if worker is None:
                self.running = False
                return None
            frame = worker.latest()
            fresh = frame is not None and frame.number != engine._drawn
            if fresh:
                engine.tag_redraw()
            elif worker.idle():
                self.running = False
                return None
        except ReferenceError:  # Blender freed the engine
            self.running = False
            return None
        return 0.03


class ViewportEngine:
    """What both engines do, F12 and in the viewport; each names its kind
    (``KIND``: final.render's renderer, and ``scene.shafts_<KIND>`` holds its
    settings) and says how to make its worker (``_make_worker``) and what
    settings need a new one (``_settings``)."""

    KIND = None
    bl_use_preview = False
    bl_use_eevee_viewport = True
    bl_use_shading_nodes_custom = False

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._worker = None
        self._exported = None
        self._last_patch = None
        self._settings_seen = None
        self._view = None
        self._drawn = 0
        self._texture = None
        self._pixels = {}
        self._timer = None

    def __del__(self):
        worker = getattr(self, "_worker", None)
        if worker is not None:
            worker.close()

    def render(self, depsgraph):
        final.render(self, depsgraph, self.KIND)

    def _viewport(self, scene):
        return getattr(scene, "shafts_" + self.KIND)

    def _full_export(self, depsgraph):
        from . import convert
        view, size = self._view
        self._exported = convert.export_scene(depsgraph, view=view, size=size)
        self._last_patch = None
        self._worker.rebuild(self._exported, self._settings_seen)

    def _send_patch(self, depsgraph):
        from . import convert
        view, size = self._view
        patch = convert.export_patch(depsgraph, self._exported, view=view, size=size)
        if patch is None:
            self._full_export(depsgraph)
        elif patch != self._last_patch:  # e.g. a selection: nothing to draw again
            self._worker.patch(patch)
        self._last_patch = patch

    def _send_changes(self, depsgraph):
        """The whole scene when the worker needs it again, else a patch."""
        if self._worker.needs_rebuild:
            self._full_export(depsgraph)
        else:
            self._send_patch(depsgraph)

    def view_update(self, context, depsgraph):
        try:
            self._view = view_of(context, self._viewport(depsgraph.scene).viewport_divider)
            settings = self._settings(depsgraph.scene)
            if self._worker is None or settings != self._settings_seen:
                if self._worker is not None:
                    self._worker.close()
                self._settings_seen = settings
                self._worker = self._make_worker(depsgraph.scene)
                self._timer = _RedrawTimer(self)
                self._full_export(depsgraph)
            else:
                self._send_changes(depsgraph)
        except Exception as e:
            self.update_stats("", "Shafts: " + describe(e))
            return
        self._timer.start()

    def view_draw(self, context, depsgraph):
        if self._worker is None:
            return
        view = view_of(context, self._viewport(depsgraph.scene).viewport_divider)
        if not same_view(view, self._view) or self._worker.needs_rebuild:
            self._view = view
            try:
                self._send_changes(depsgraph)
            except Exception as e:
                self.update_stats("", "Shafts: " + describe(e))
            self._timer.start()
        frame = self._worker.latest()
        if self._worker.error:
            self.update_stats("", "Shafts: " + self._worker.error)
        if frame is None:
            return
        if frame.number != self._drawn:
            self._texture = make_texture(frame.rgb, self._pixels)
            self._drawn = frame.number
            self.update_stats("", self._frame_stats(frame))
        if not self._worker.idle():
            self._timer.start()
        draw_texture(self, depsgraph.scene, self._texture, context.region)


class ShaftsSweepEngine(ViewportEngine, bpy.types.RenderEngine):
    bl_idname = "SHAFTS_SWEEP"
    bl_label = "Shafts Sweep"
    KIND = "sweep"

    def _settings(self, scene):
        return sweep_options(scene.shafts_sweep)

    def _make_worker(self, scene):
        from .viewport import SweepWorker
        return SweepWorker(options=self._settings_seen)

    def _frame_stats(self, frame):
        stats = frame.stats or {}
        return "Shafts sweep | %.0f ms | planes %s | programs compiled %s" % (
            frame.seconds * 1000, stats.get("planes", "?"), stats.get("programs_compiled", "?"))


class ShaftsTracerEngine(ViewportEngine, bpy.types.RenderEngine):
    bl_idname = "SHAFTS_TRACER"
    bl_label = "Shafts Tracer"
    KIND = "tracer"

    def _settings(self, scene):
        name, arguments = tracer_arguments(scene.shafts_tracer)
        return name, arguments, scene.shafts_tracer.viewport_spp

    def _make_worker(self, scene):
        from .viewport import TracerWorker
        name, arguments, most = self._settings_seen
        return TracerWorker(name, arguments, spp_steps(most))

    def _frame_stats(self, frame):
        return "Shafts tracer | spp %s | %.2f s" % ((frame.stats or {}).get("spp", "?"),
                                                    frame.seconds)


def make_texture(rgb, cache):
    """A GPUTexture of a frame (rows from the top, as the library gives
    them; the texture's rows run from the bottom)."""
    import gpu
    from .result import rgba_bottom_up
    h, w = rgb.shape[:2]
    pixels = rgba_bottom_up(rgb, cache)
    buffer = gpu.types.Buffer('FLOAT', pixels.size, pixels.reshape(-1))
    return gpu.types.GPUTexture((w, h), format='RGBA16F', data=buffer)


def draw_texture(engine, scene, texture, region):
    """Draws the frame over the region through Blender's display transform
    (view transform, look, exposure: as the render window shows F12)."""
    import gpu
    from gpu_extras.presets import draw_texture_2d
    gpu.state.blend_set('ALPHA_PREMULT')
    engine.bind_display_space_shader(scene)
    draw_texture_2d(texture, (0, 0), region.width, region.height)
    engine.unbind_display_space_shader()
    gpu.state.blend_set('NONE')


classes = (ShaftsSweepEngine, ShaftsTracerEngine)
