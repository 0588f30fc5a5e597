"""Progress of a validation run: how many of its renderings are done, the
time left, and which scene or hard case each one is for.

ProgressExecutor wraps an executor (runs.LocalExecutor, slurm.SlurmExecutor)
and knows every run of the validation ahead (the same plan the Slurm
executor renders). Each rendering it starts is announced as

  [12/87 renderings, 3 min 20 s left] teapot_spot: rendering gl_shafts: planes 25

The time left is each remaining run's estimate from its adapter's cost model
(renderers.Adapter: start-up plus seconds per megapixel and unit of work),
corrected by how long the runs of the same renderer have actually taken
(those rendered so far and those the cache holds, as they recorded it; for
a renderer not seen yet, of all renderers). Runs the cache already holds
take no time and are counted as done at once.
"""

import time


def estimate(run):
    """The cost model's seconds for one planned run (runs.Run)."""
    a, s = run.adapter, run.scene
    megapixels = s.width * s.height / 1e6
    return a.startup_seconds + megapixels * a.work(run.params) * a.seconds_per_megapixel


def fmt_left(seconds):
    """A time left for people: whole seconds below a minute, then minutes
    and seconds, then hours and minutes."""
    s = int(round(seconds))
    if s < 60:
        return "%d s" % s
    if s < 3600:
        return "%d min %02d s" % (s // 60, s % 60)
    return "%d h %02d min" % (s // 3600, (s % 3600) // 60)


class ProgressExecutor:
    """An executor that counts and announces (see the module's text)."""

    def __init__(self, inner, cache, planned, retry_failed=False, clock=time.perf_counter):
        self.inner, self.clock = inner, clock
        self.name = inner.name
        self.todo = {}     # key -> estimate, runs the cache lacks
        self.done = set()  # keys finished in this validation or cached
        self.spent = {}    # adapter name -> [seconds taken, seconds estimated]
        for r in planned:
            if r.key in self.todo or r.key in self.done:
                continue
            cached = cache.load(r.key)
            if cached is not None and (cached.get("status") == "ok" or not retry_failed):
                self.done.add(r.key)
                # What the cached runs took calibrates the estimates too.
                if cached.get("wall_seconds"):
                    spent = self.spent.setdefault(r.adapter.name, [0.0, 0.0])
                    spent[0] += cached["wall_seconds"]
                    spent[1] += estimate(r)
            else:
                self.todo[r.key] = (r.adapter.name, estimate(r))
        self.total = len(self.todo) + len(self.done)

    def __getattr__(self, name):
        # prefetch, info, failed, ...: the wrapped executor's.
        return getattr(self.inner, name)

    def seconds_left(self):
        """The estimated seconds the runs not yet done will take."""
        taken = sum(v[0] for v in self.spent.values())
        guessed = sum(v[1] for v in self.spent.values())
        overall = taken / guessed if guessed > 0 else 1.0
        left = 0.0
        for name, est in self.todo.values():
            t, g = self.spent.get(name, (0.0, 0.0))
            left += est * (t / g if g > 0 else overall)
        return left

    def status(self):
        """"[12/87 renderings, 3 min 20 s left]"."""
        return "[%d/%d renderings, %s left]" % (len(self.done) + 1, self.total,
                                                fmt_left(self.seconds_left()))

    def run(self, run, say=None):
        key = run.key
        if key not in self.todo and key not in self.done:
            self.todo[key] = (run.adapter.name, estimate(run))  # not planned
            self.total += 1
        prefix = self.status()
        scene = run.describe.get("scene", "")
        start = self.clock()
        result = self.inner.run(
            run, say=(lambda m: say("%s %s: %s" % (prefix, scene, m))) if say else None)
        took = self.clock() - start
        if key in self.todo:
            name, est = self.todo.pop(key)
            if not result.get("cached"):
                spent = self.spent.setdefault(name, [0.0, 0.0])
                spent[0] += took
                spent[1] += est
        self.done.add(key)
        return result

