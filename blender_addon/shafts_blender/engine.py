"""The two render engines: SHAFTS_SWEEP (gl_shafts' plane sweep) and
SHAFTS_TRACER (lmm_tracer: the reference, Whitted or light meshes).

F12 goes through final.render. The sweep's viewport keeps a ViewportWorker
(viewport.py): view_update and view_draw send it changes and draw the
newest finished frame as a texture with Blender's gpu module; a timer on
Blender's main thread tags a redraw when the worker has a new frame.
"""
import weakref

import bpy

from . import final
from .properties import sweep_options


def view_of(context):
    """(view_matrix, projection_matrix) and (width, height) of the 3D view
    being drawn."""
    region, rv3d = context.region, context.region_data
    return (rv3d.view_matrix.copy(), rv3d.window_matrix.copy()), (region.width, region.height)


def same_view(a, b):
    if a is None or b is None:
        return False
    (va, pa), sa = a
    (vb, pb), sb = b
    return sa == sb and va == vb and pa == pb


class _RedrawTimer:
    """Polls a worker from Blender's main thread (bpy.app.timers) and tags
    the engine's viewport for a redraw when a newer frame is ready; stops
    when the engine is gone or nothing is pending."""

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
            if engine is None or engine._worker is None:
                self.running = False
                return None
            frame = engine._worker.latest()
            if frame is not None and frame.number != engine._drawn:
                engine.tag_redraw()
            if engine._worker.idle() and (frame is None or frame.number == engine._drawn):
                self.running = False
                return None
        except ReferenceError:  # Blender freed the engine
            self.running = False
            return None
        return 0.03


class ShaftsSweepEngine(bpy.types.RenderEngine):
    bl_idname = "SHAFTS_SWEEP"
    bl_label = "Shafts Sweep"
    bl_use_preview = False
    bl_use_eevee_viewport = True
    bl_use_shading_nodes_custom = False

    def __init__(self):
        self._worker = None
        self._exported = None
        self._options = None
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
        final.render(self, depsgraph, "sweep")

    # The viewport.
    def _full_export(self, depsgraph):
        from . import convert
        view, size = self._view
        self._exported = convert.export_scene(depsgraph, view=view, size=size)
        self._options = sweep_options(depsgraph.scene.shafts_sweep)
        self._worker.rebuild(self._exported, self._options)

    def _send_patch(self, depsgraph):
        from . import convert
        view, size = self._view
        patch = convert.export_patch(depsgraph, self._exported, view=view, size=size)
        if patch is None:
            self._full_export(depsgraph)
        else:
            self._worker.patch(patch)

    def view_update(self, context, depsgraph):
        from .viewport import ViewportWorker
        try:
            self._view = view_of(context)
            if self._worker is None:
                self._worker = ViewportWorker()
                self._timer = _RedrawTimer(self)
                self._full_export(depsgraph)
            elif self._worker.needs_rebuild or \
                    sweep_options(depsgraph.scene.shafts_sweep) != self._options:
                self._full_export(depsgraph)
            else:
                self._send_patch(depsgraph)
        except Exception as e:
            self.update_stats("", "Shafts: " + final.describe(e))
            return
        self._timer.start()

    def view_draw(self, context, depsgraph):
        if self._worker is None:
            return
        view = view_of(context)
        if not same_view(view, self._view):
            self._view = view
            try:
                self._send_patch(depsgraph)
            except Exception as e:
                self.update_stats("", "Shafts: " + final.describe(e))
            self._timer.start()
        frame = self._worker.latest()
        if self._worker.error:
            self.update_stats("", "Shafts: " + self._worker.error)
        if frame is None:
            return
        if frame.number != self._drawn:
            self._texture = make_texture(frame.rgb, self._pixels)
            self._drawn = frame.number
            stats = frame.stats or {}
            self.update_stats("", "Shafts sweep | %.0f ms | programs compiled %s"
                              % (frame.seconds * 1000, stats.get("programs_compiled", "?")))
        if not self._worker.idle():
            self._timer.start()
        draw_texture(self, depsgraph.scene, self._texture, context.region)


class ShaftsTracerEngine(bpy.types.RenderEngine):
    bl_idname = "SHAFTS_TRACER"
    bl_label = "Shafts Tracer"
    bl_use_preview = False
    bl_use_eevee_viewport = True
    bl_use_shading_nodes_custom = False

    def render(self, depsgraph):
        final.render(self, depsgraph, "tracer")


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
