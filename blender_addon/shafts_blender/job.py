"""A render call on a worker thread, watched from Blender's render thread.

shafts.py's calls release the GIL while the library works (ctypes does), so
the thread that Blender gave the engine stays free to poll
``RenderEngine.test_break()``, to raise the library's cancel flag and to
report progress. No bpy here: the engine passes its own callbacks.
"""
import threading
import time


class Progress:
    """Written from the library's worker threads (one tuple assignment,
    cheap and atomic under the GIL), read by the watcher."""

    def __init__(self):
        self.done, self.total = 0, 0

    def __call__(self, done, total):
        self.done, self.total = done, total

    def fraction(self):
        done, total = self.done, self.total
        return min(1.0, done / total) if total > 0 else 0.0


class Job:
    """Runs ``fn()`` on its own thread; ``result`` or ``error`` (the
    exception it raised) once it ended."""

    def __init__(self, fn, name="shafts-render"):
        self.result = None
        self.error = None
        self.seconds = 0.0
        self._fn = fn
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)

    def _run(self):
        start = time.perf_counter()
        try:
            self.result = self._fn()
        except BaseException as e:  # reported by the watcher, never lost
            self.error = e
        self.seconds = time.perf_counter() - start

    def start(self):
        self._thread.start()
        return self

    def watch(self, test_break, cancel=None, on_tick=None, interval=0.05):
        """Waits for the job, calling ``on_tick()`` every ``interval``
        seconds; when ``test_break()`` turns true, sets ``cancel`` (an
        object with ``.set()``) once. Returns True if a break was asked."""
        asked = False
        while self._thread.is_alive():
            self._thread.join(interval)
            if not asked and test_break():
                asked = True
                if cancel is not None:
                    cancel.set()
            if on_tick is not None:
                on_tick()
        return asked
