"""Running renderers: timed commands and the run cache.

Every rendering is a run, identified by a key: the hash of the scene's
content key, the renderer's name and version, and the settings. A run's
results live in CACHE/runs/KEY/: the image (image.exr), the log (log.txt)
and result.json, which is written last and atomically. A run whose
result.json exists is done; anything else in its directory is the debris of
an interrupted run and is thrown away when the run is redone. So re-running
the validation renders only what changed, and an interrupted validation
resumes where it stopped.
"""

import hashlib
import json
import os
import shutil
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

from .scenes import write_atomic

# Bump when the meaning of a cached result changes (what the adapters
# record, how they time); every run is then redone.
CACHE_FORMAT = 1


class RunFailed(Exception):
    """A renderer failed: its message goes into the report."""


class NotExported(RunFailed):
    """The exporter refuses the scene for this renderer (a feature it does
    not write yet, e.g. the atmosphere for Blender): not a failure of the
    renderer, reported as "not exported" with the exporter's reason. The
    run's key holds the exporter's SHA-256, so the run is tried again as
    soon as a new exporter writes the scene."""


def run_key(scene_key, renderer, version, params):
    """The cache key of one rendering."""
    blob = json.dumps({"format": CACHE_FORMAT, "scene": scene_key,
                       "renderer": renderer, "version": version,
                       "params": params}, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()


def file_fingerprint(path):
    """A version string for a file: its SHA-256 (the same bytes give the same
    version, whenever and wherever they were built)."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()[:20]


def command(cmd, cwd=None, env=None, timeout=None, log=None):
    """Runs cmd (a list), appending its output to the open file `log`.
    Returns (wall-clock seconds, the output as text); raises RunFailed if
    the command cannot start, exits non-zero or takes longer than `timeout`
    seconds."""
    if log is not None:
        log.write("$ %s\n" % " ".join(str(c) for c in cmd))
        log.flush()
    full_env = None
    if env:
        full_env = dict(os.environ)
        full_env.update(env)
    start = time.perf_counter()
    try:
        proc = subprocess.run([str(c) for c in cmd], cwd=cwd, env=full_env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout, check=False)
    except FileNotFoundError as e:
        raise RunFailed("cannot run %s: %s" % (cmd[0], e)) from e
    except subprocess.TimeoutExpired as e:
        if log is not None and e.output:
            log.write(e.output.decode(errors="replace"))
        raise RunFailed("%s took longer than %g s and was stopped"
                        % (Path(str(cmd[0])).name, timeout)) from e
    wall = time.perf_counter() - start
    out = proc.stdout.decode(errors="replace")
    if log is not None:
        log.write(out)
        log.write("[exit %d after %.3f s]\n" % (proc.returncode, wall))
        log.flush()
    if proc.returncode != 0:
        tail = " | ".join(line for line in out.strip().splitlines()[-3:])
        raise RunFailed("%s exited with status %d: %s"
                        % (Path(str(cmd[0])).name, proc.returncode, tail[-400:]))
    return wall, out


class RunCache:
    """The directory of cached runs."""

    def __init__(self, root):
        self.root = Path(root)

    def dir(self, key):
        return self.root / "runs" / key[:2] / key

    def load(self, key):
        """The cached result of a finished run, or None. A successful run
        counts only if its image is still there."""
        d = self.dir(key)
        try:
            result = json.loads((d / "result.json").read_text())
        except (OSError, ValueError):
            return None
        if result.get("status") == "ok" and not (d / "image.exr").exists():
            return None
        result["image"] = str(d / "image.exr")
        result["log"] = str(d / "log.txt")
        return result

    def store(self, key, result):
        write_atomic(self.dir(key) / "result.json",
                     json.dumps(result, indent=1, sort_keys=True) + "\n")


def execute(cache, key, describe, render, retry_failed=False, say=None):
    """Returns the result of one run from the cache, or renders it.

    `render(work, log)` renders into the empty directory `work`, writing its
    output to the open file `log`, and returns a dict with `image` (the
    EXR it wrote), `wall_seconds` (the orchestrator's timing of the render
    command) and optionally `tool_seconds` (the renderer's own timing) and
    `notes`. It raises RunFailed on failure. `describe` (a dict: renderer,
    label, params, version, scene) is stored with the result."""
    cached = cache.load(key)
    if cached is not None and (cached.get("status") == "ok" or not retry_failed):
        cached["cached"] = True
        return cached
    d = cache.dir(key)
    work = d / "work"
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    for stale in ("result.json", "image.exr"):
        if (d / stale).exists():
            (d / stale).unlink()
    if say:
        say("rendering %s: %s" % (describe.get("renderer"), describe.get("label")))
    result = dict(describe)
    result["started"] = time.strftime("%Y-%m-%dT%H:%M:%S")
    with open(d / "log.txt", "w", encoding="utf-8") as log:
        try:
            out = render(work, log)
            os.replace(out["image"], d / "image.exr")
            result.update({k: v for k, v in out.items() if k != "image"})
            result["status"] = "ok"
        except NotExported as e:
            result["status"] = "not_exported"
            result["error"] = str(e)
            log.write("NOT EXPORTED: %s\n" % e)
        except RunFailed as e:
            result["status"] = "failed"
            result["error"] = str(e)
            log.write("FAILED: %s\n" % e)
    shutil.rmtree(work, ignore_errors=True)
    cache.store(key, result)
    result["image"] = str(d / "image.exr")
    result["log"] = str(d / "log.txt")
    result["cached"] = False
    return result


@dataclass
class Run:
    """One rendering of a sweep, before it is rendered: its cache key, the
    description stored with its result, and what renders it (an adapter of
    renderers.py, the prepared scene, the settings)."""

    key: str
    version: str         # the renderer's version, part of the key
    describe: dict
    adapter: object
    scene: object        # scenes.PreparedScene: path, width, height
    params: dict


def plan_run(ctx, adapter, scene, params, label):
    """The Run of `adapter` on a prepared scene at one setting."""
    version = adapter.version(ctx)
    key = run_key(scene.key, adapter.name, version, params)
    describe = {"renderer": adapter.name, "label": label, "params": params,
                "scene": scene.name}
    return Run(key, version, describe, adapter, scene, params)


class LocalExecutor:
    """Renders every run here, one at a time, when it is asked for (the
    default). The Slurm executor (slurm.py) renders a sweep's runs as a job
    array first and then answers from the cache; both give the same results."""

    name = "local"

    def __init__(self, ctx, cache, retry_failed=False):
        self.ctx, self.cache, self.retry_failed = ctx, cache, retry_failed

    def prefetch(self, planned, say):
        """Nothing to do ahead: runs render when they are asked for."""
        return True

    def run(self, run, say=None):
        return execute(self.cache, run.key, run.describe,
                       lambda work, log: run.adapter.render(self.ctx, run.scene.path,
                                                            run.params, work, log),
                       retry_failed=self.retry_failed, say=say)

    def info(self):
        return {"name": self.name}
