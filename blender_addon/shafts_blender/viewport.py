"""The viewport's renderer thread: it alone owns the library's scene (and,
for the sweep, its live gl_shafts renderer), so the library's GL context
never becomes current on Blender's thread, and no library call runs there.

Blender's side (view_update, view_draw) only queues work: ``rebuild`` with a
converted scene when the structure changed, ``patch`` with a scene patch
(camera, lights, medium, transforms) otherwise. The thread folds what is
queued into one step (a rebuild drops the patches before it; patches merge,
later values winning), applies it, renders and publishes the frame.
SweepWorker applies a patch with Scene.update and SweepRenderer.sync (no
program compiles unless a structural switch changed) and draws one frame;
TracerWorker refines progressively, rendering again with more samples per
pixel while nothing new is queued, and cancels a render that new work makes
stale. No bpy here: tests drive the workers in background mode, where there
is no window.
"""
import threading
import time

from .errors import describe, is_cancelled


def merge_patches(old, new):
    """One patch doing what ``old`` then ``new`` do."""
    if old is None:
        return dict(new)
    merged = dict(old)
    for key, value in new.items():
        if key == "transforms" and isinstance(merged.get(key), list) \
                and isinstance(value, list) and len(value) == len(merged[key]):
            merged[key] = [n if n is not None else o for o, n in zip(merged[key], value)]
        else:
            merged[key] = value
    return merged


class Frame:
    """A finished image: ``rgb`` (h, w, 3) float32 rows from the top, the
    renderer's ``stats`` dict, a ``number`` counting frames, and ``seconds``
    (the update, sync and rendering that made it)."""

    def __init__(self, number, rgb, stats, seconds):
        self.number, self.rgb, self.stats, self.seconds = number, rgb, stats, seconds


class ViewportWorker:
    """The queue and the thread. ``on_frame()`` is called from the worker
    thread after each new frame; ``error`` holds the last failure (a string);
    ``needs_rebuild`` turns true when a patch was refused (e.g. a light's
    type changed), and the next ``rebuild`` clears it."""

    def __init__(self, options=None, on_frame=None):
        from . import shafts
        self._shafts = shafts
        self._options = options
        self._on_frame = on_frame
        self._cond = threading.Condition()
        self._rebuild = None
        self._patch = None
        self._closing = False
        self._busy = False
        self._more = False  # the subclass wants to render again (refinement)
        self._scene = None
        self._count = 0
        self.frame = None
        self.error = None
        self.needs_rebuild = False
        self._thread = threading.Thread(target=self._loop, name="shafts-viewport", daemon=True)
        self._thread.start()

    # Blender's side: cheap, never blocks on the library.
    def rebuild(self, exported, options=None):
        """Replace the scene with a converted one (convert's Export)."""
        with self._cond:
            self._rebuild = (exported.text, exported.meshes, options or self._options)
            self._patch = None
            self.needs_rebuild = False
            self._interrupt()
            self._cond.notify_all()

    def patch(self, patch):
        """Apply a patch dict (convert.export_patch) to the current scene."""
        if not patch:
            return
        with self._cond:
            self._patch = merge_patches(self._patch, patch)
            self._interrupt()
            self._cond.notify_all()

    def idle(self):
        """True when nothing is queued, rendering or left to refine."""
        return not self._busy and not self._more and self._rebuild is None \
            and self._patch is None

    def latest(self):
        """The newest finished Frame, or None."""
        return self.frame

    def wait_frame(self, after=0, timeout=60.0):
        """Blocks until a frame numbered above ``after`` is done and nothing
        is queued (tests use it); returns it, or None on timeout or error."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while True:
                queued = self._busy or self._rebuild is not None or self._patch is not None
                newer = self.frame is not None and self.frame.number > after
                if not queued and (newer or self.error is not None):
                    return self.frame if newer else None
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self._cond.wait(left)

    def close(self):
        """Stops the thread; the library's objects are freed on it."""
        with self._cond:
            self._closing = True
            self._interrupt()
            self._cond.notify_all()
        self._thread.join()

    # The worker thread.
    def _loop(self):
        while True:
            with self._cond:
                while not (self._closing or self._rebuild or self._patch or self._more):
                    self._cond.wait()
                if self._closing:
                    break
                rebuild, patch = self._rebuild, self._patch
                self._rebuild = self._patch = None
                self._busy = True
            try:
                start = time.perf_counter()
                if rebuild is not None:
                    self._free()
                    text, meshes, options = rebuild
                    self._scene = self._shafts.Scene.from_json(
                        text, name="viewport.json", base_dir=".", meshes=meshes)
                    self._created(options)
                elif patch is not None and self._scene is not None:
                    try:
                        changed = self._scene.update(patch)
                    except self._shafts.ShaftsError:
                        self.needs_rebuild = True
                        raise
                    self._changed(changed)
                if self._scene is not None:
                    self._render(start)
            except Exception as e:  # kept for view_draw to report
                self._more = False
                if not is_cancelled(e):
                    self.error = describe(e)
            with self._cond:
                self._busy = False
                self._cond.notify_all()
        self._free()

    def _publish(self, rgb, stats, start):
        self._count += 1
        self.error = None
        self.frame = Frame(self._count, rgb, stats, time.perf_counter() - start)
        if self._on_frame is not None:
            self._on_frame()

    def _free(self):
        self._release()
        if self._scene is not None:
            self._scene.close()
            self._scene = None

    # What the engines' workers define.
    def _interrupt(self):
        """Called under the lock when new work arrives."""

    def _created(self, options):
        """A new scene is in self._scene."""

    def _changed(self, changed):
        """A patch changed the scene (SH_CHANGED_* bits)."""

    def _render(self, start):
        """Renders and publishes one frame; sets self._more to be called
        again while nothing is queued."""
        raise NotImplementedError

    def _release(self):
        """Frees what _created made."""


class SweepWorker(ViewportWorker):
    """The sweep's viewport: a live SweepRenderer, synced after patches."""

    def __init__(self, options=None, on_frame=None, backend="auto"):
        self._backend = backend
        self._renderer = None
        super().__init__(options, on_frame)

    def _created(self, options):
        self._renderer = self._shafts.SweepRenderer(self._scene, options=options, live=True,
                                                    backend=self._backend)

    def _changed(self, changed):
        if changed:
            self._renderer.sync(changed)

    def _render(self, start):
        rgb, stats = self._renderer.draw()
        self._publish(rgb, stats, start)

    def _release(self):
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None


class TracerWorker(ViewportWorker):
    """The tracer's viewport: progressive refinement. After each change it
    renders at ``steps[0]`` samples per pixel, then at each next step while
    nothing new is queued; new work cancels the render under way."""

    def __init__(self, function, arguments, steps, on_frame=None):
        self._function, self._arguments, self._steps = function, dict(arguments), list(steps)
        self._level = 0
        self._cancel = None
        super().__init__(None, on_frame)

    def _interrupt(self):
        if self._cancel is not None:
            self._cancel.set()

    def _created(self, options):
        self._level = 0

    def _changed(self, changed):
        self._level = 0

    def _render(self, start):
        spp = self._steps[self._level]
        with self._cond:
            self._cancel = self._shafts.CancelFlag()
            cancel = self._cancel
        fn = getattr(self._shafts, self._function)
        rgb, stats = fn(self._scene, cancel=cancel, **dict(self._arguments, spp=spp))
        stats = dict(stats or {}, spp=spp)
        self._level += 1
        self._more = self._level < len(self._steps)
        self._publish(rgb, stats, start)
