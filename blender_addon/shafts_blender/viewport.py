"""The viewport's renderer thread: it alone owns the library's scene and its
live gl_shafts renderer, so the library's GL context never becomes current
on Blender's thread (and no library call runs there at all).

Blender's side (view_update, view_draw) only queues work: ``rebuild`` with a
converted scene when the structure changed, ``patch`` with a scene patch
(camera, lights, medium, transforms) otherwise. The thread folds what is
queued into one step (a rebuild drops the patches before it; patches merge,
later values winning), applies it (Scene.update, then SweepRenderer.sync
with the changed bits: no program compiles unless a structural switch
changed), draws, and publishes the frame. No bpy here: tests drive it in
background mode, where there is no window.
"""
import threading
import time


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
    (the update, sync and draw that made it)."""

    def __init__(self, number, rgb, stats, seconds):
        self.number, self.rgb, self.stats, self.seconds = number, rgb, stats, seconds


class ViewportWorker:
    """Owns a thread, a shafts.Scene and a shafts.SweepRenderer(live=True).

    ``on_frame()`` is called from the worker thread after each new frame (the
    engine tags a redraw there). ``error`` holds the last failure (a string);
    ``needs_rebuild`` turns true when a patch was refused (e.g. a light's
    type changed), and the next ``rebuild`` clears it."""

    def __init__(self, options=None, on_frame=None, backend="auto"):
        from . import shafts
        self._shafts = shafts
        self._options = options
        self._backend = backend
        self._on_frame = on_frame
        self._cond = threading.Condition()
        self._rebuild = None
        self._patch = None
        self._closing = False
        self._busy = False
        self._scene = None
        self._renderer = None
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
            self._cond.notify()

    def patch(self, patch):
        """Apply a patch dict (convert.export_patch) to the current scene."""
        if not patch:
            return
        with self._cond:
            self._patch = merge_patches(self._patch, patch)
            self._cond.notify()

    def idle(self):
        """True when nothing is queued or being drawn."""
        return not self._busy and self._rebuild is None and self._patch is None

    def latest(self):
        """The newest finished Frame, or None."""
        return self.frame

    def wait_frame(self, after=0, timeout=60.0):
        """Blocks until a frame numbered above ``after`` is done and nothing
        is queued (tests use it); returns it, or None on timeout or error."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while True:
                idle = not self._busy and self._rebuild is None and self._patch is None
                if idle and (self.frame is not None and self.frame.number > after
                             or self.error is not None):
                    return self.frame if self.frame and self.frame.number > after else None
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self._cond.wait(left)

    def close(self):
        """Stops the thread and frees the renderer and scene (on the thread)."""
        with self._cond:
            self._closing = True
            self._cond.notify()
        self._thread.join()

    # The worker thread.
    def _loop(self):
        while True:
            with self._cond:
                while not (self._closing or self._rebuild or self._patch):
                    self._cond.wait()
                if self._closing:
                    break
                rebuild, patch = self._rebuild, self._patch
                self._rebuild = self._patch = None
                self._busy = True
            try:
                self._step(rebuild, patch)
            except Exception as e:  # kept for view_draw to report
                self.error = describe_error(e)
            with self._cond:
                self._busy = False
                self._cond.notify_all()
        self._free()

    def _free(self):
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
        if self._scene is not None:
            self._scene.close()
            self._scene = None

    def _step(self, rebuild, patch):
        shafts = self._shafts
        start = time.perf_counter()
        if rebuild is not None:
            self._free()
            text, meshes, options = rebuild
            self._scene = shafts.Scene.from_json(text, name="viewport.json", base_dir=".",
                                                 meshes=meshes)
            self._renderer = shafts.SweepRenderer(self._scene, options=options, live=True,
                                                  backend=self._backend)
        elif patch is not None and self._renderer is not None:
            try:
                changed = self._scene.update(patch)
            except shafts.ShaftsError:
                self.needs_rebuild = True
                raise
            if changed:
                self._renderer.sync(changed)
        else:
            return
        rgb, stats = self._renderer.draw()
        self._count += 1
        self.error = None
        self.frame = Frame(self._count, rgb, stats, time.perf_counter() - start)
        if self._on_frame is not None:
            self._on_frame()


def describe_error(error):
    from .final import describe
    return describe(error)
