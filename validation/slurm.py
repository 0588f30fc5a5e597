"""The Slurm executor: a sweep's renders as tasks of Slurm job arrays.

validate.py --executor slurm plans every run of the sweep first (the
scenes' references and settings, the hard cases), and prefetch() renders
the ones the run cache lacks on the cluster:

1. a probe job checks, on a node, that the cache directory and the source
   and build trees are there at the same paths and that the renderers are
   the same build (validation.slurm_task --probe); if not, the sweep stops with
   the probe's message before anything else is submitted;
2. the runs are grouped by renderer and by their time and memory limits
   (Adapter.limits: the renderer's cost model and the image size), and each
   group is one `sbatch --array=0-(n-1)%P` of validation.slurm_task over a
   manifest, its log per task in CACHE/slurm/SWEEP/logs/JOB_TASK.log;
3. the executor polls squeue until the arrays have left the queue; a task
   whose run has no result in the cache failed on the Slurm side
   (cancelled, node failure, time or memory limit): it is resubmitted, up
   to `retries` times, with twice the time after a TIMEOUT and twice the
   memory after OUT_OF_MEMORY. A task that cannot see the cache (exit 3)
   or runs another build (exit 4) is not retried.

Then the sweep compares as with the local executor, reading every run from
the cache (run()): the same images, so the same results and pages. A run
whose task failed for good is reported failed with its Slurm state and log,
and is not cached, so the next sweep submits it again: an interrupted or
partly failed sweep resumes, and a re-run renders only what is missing.
"""

import json
import math
import os
import re
import shlex
import shutil
import subprocess
import time
from collections import OrderedDict
from pathlib import Path

from .scenes import write_atomic

HERE = Path(__file__).resolve().parent
# The package the task runs (python3 -m validation.slurm_task) is
# imported from the source tree that holds validation/.
PACKAGE_ROOT = HERE.parent
# Slurm's default MaxArraySize is 1001: array indices stay below 1000.
MAX_ARRAY = 1000
NO_CACHE, MISMATCH = 3, 4


class SlurmError(Exception):
    """The sweep cannot go on with Slurm (no sbatch, the nodes cannot see
    the cache): the message says why."""


def _slurm(cmd, timeout=60):
    """Runs a Slurm command; returns its output or raises SlurmError."""
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=timeout, check=False)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise SlurmError("%s: %s" % (cmd[0], e)) from e
    if p.returncode != 0:
        raise SlurmError("%s failed (exit %d): %s" % (" ".join(cmd[:2]), p.returncode,
                                                     p.stderr.decode(errors="replace").strip()))
    return p.stdout.decode(errors="replace")


def _indices(spec):
    """The task indices of an array spec: "3", "4-6", "1,3-5%2"."""
    out = []
    for part in spec.split("%")[0].strip("[]").split(","):
        if "-" in part:
            a, b = part.split("-", 1)
            out.extend(range(int(a), int(b) + 1))
        elif part.strip().isdigit():
            out.append(int(part))
    return out


def task_states(job):
    """{task index: (state, exit code)} of an array job: from sacct where
    accounting is kept, else from scontrol (which remembers finished jobs
    for MinJobAge, 5 minutes by default)."""
    states = {}
    try:
        out = _slurm(["sacct", "-n", "-P", "-X", "-j", str(job), "-o", "JobID,State,ExitCode"])
        for line in out.splitlines():
            jid, state, code = (line.split("|") + ["", ""])[:3]
            if "_" in jid:
                for i in _indices(jid.split("_", 1)[1]):
                    states[i] = (state.split()[0], code)
    except SlurmError:
        pass
    if states:
        return states
    try:
        out = _slurm(["scontrol", "-o", "show", "job", str(job)])
    except SlurmError:
        return states
    for line in out.splitlines():
        f = dict(re.findall(r"(\w+)=(\S*)", line))
        if "ArrayTaskId" in f:
            for i in _indices(f["ArrayTaskId"]):
                states[i] = (f.get("JobState", "UNKNOWN"), f.get("ExitCode", ""))
    return states


class SlurmExecutor:
    """Renders a sweep's missing runs on Slurm (see the module's text)."""

    name = "slurm"

    def __init__(self, ctx, cache, retry_failed=False, partition=None, account=None,
                 parallel=32, retries=2, cpus=1, setup=None, sbatch_args=(), poll=0.5):
        self.ctx, self.cache, self.retry_failed = ctx, cache, retry_failed
        self.partition, self.account = partition, account
        self.parallel, self.retries, self.cpus = parallel, retries, cpus
        self.setup, self.sbatch_args, self.poll = setup, list(sbatch_args), poll
        self.rendered = set()     # keys rendered by this sweep's tasks
        self.failed = {}          # key -> why its task failed for good
        self.jobs = []            # every job id submitted
        self.tasks = 0

    def info(self):
        """What results.json records about the executor."""
        return {"name": self.name, "jobs": self.jobs, "tasks": self.tasks,
                "failed_tasks": len(self.failed)}

    # -- the sweep's side ----------------------------------------------------

    def run(self, run, say=None):
        """The result of a run after prefetch(): from the cache, or a
        failure naming the task's Slurm state and log (not cached)."""
        if run.key in self.failed:
            return dict(run.describe, status="failed", error=self.failed[run.key],
                        cached=False, image=None, log=None)
        result = self.cache.load(run.key)
        if result is None or (result["status"] != "ok" and self.retry_failed
                              and run.key not in self.rendered):
            # Not planned (a bug) or rendered by nobody: render it here
            # rather than report a hole.
            from runs import LocalExecutor
            if say:
                say("not rendered on Slurm: %s" % run.describe.get("label"))
            result = LocalExecutor(self.ctx, self.cache, self.retry_failed).run(run, say)
            self.rendered.add(run.key)
            return result
        result["cached"] = run.key not in self.rendered
        return result

    def prefetch(self, planned, say):
        """Renders every planned run the cache lacks (or that failed, with
        retry_failed) as Slurm tasks and waits for them. Raises SlurmError
        if Slurm cannot be used or the nodes cannot see the cache."""
        todo = OrderedDict()
        for r in planned:
            if r.key in todo:
                continue
            cached = self.cache.load(r.key)
            if cached is None or (cached["status"] != "ok" and self.retry_failed):
                todo[r.key] = r
        if not todo:
            say("slurm: all %d runs are in the cache" % len(planned))
            return
        for tool in ("sbatch", "squeue", "scontrol"):
            if not shutil.which(tool):
                raise SlurmError("%s is not on PATH (Slurm's clients; tools/slurm_local.sh "
                                 "starts a single-node cluster)" % tool)
        sweep = self.cache.root.resolve() / "slurm" / (
            "%s-%d" % (time.strftime("%Y%m%d-%H%M%S"), os.getpid()))
        (sweep / "logs").mkdir(parents=True)
        for key in todo:
            # Only a result written by this sweep's task counts.
            stale = self.cache.dir(key) / "result.json"
            if stale.exists():
                stale.unlink()
        header = {"root": str(self.ctx.root), "build": str(self.ctx.build),
                  "mode": self.ctx.mode, "timeout": self.ctx.timeout,
                  "warm_frames": self.ctx.warm_frames,
                  "cache": str(self.cache.root.resolve()),
                  "versions": {r.adapter.name: r.version
                               for r in todo.values()}}
        script = sweep / "task.sh"
        setup = Path(self.setup).read_text() if self.setup else ""
        write_atomic(script, "#!/bin/bash\n# One render of a validation sweep "
                     "(validation/slurm.py).\n%s\nexport PYTHONPATH=%s${PYTHONPATH:+:$PYTHONPATH}\n"
                     "exec python3 -m validation.slurm_task \"$@\"\n"
                     % (setup, shlex.quote(str(PACKAGE_ROOT))))
        script.chmod(0o755)

        arrays = self._arrays(todo.values(), header, sweep)
        self.tasks = len(todo)
        try:
            self._probe(sweep, arrays[0]["manifest"], say)
            say("slurm: %d runs in %d arrays (%s)" % (len(todo), len(arrays), sweep))
            self._render(arrays, say)
        except KeyboardInterrupt:
            self._cancel()
            raise

    # -- submission ----------------------------------------------------------

    def _arrays(self, runs, header, sweep):
        groups = OrderedDict()
        for r in runs:
            limits = r.adapter.limits(self.ctx, r.scene, r.params)
            groups.setdefault((r.adapter.name,) + limits, []).append(r)
        arrays = []
        for (name, seconds, mb), members in groups.items():
            for start in range(0, len(members), MAX_ARRAY):
                chunk = members[start:start + MAX_ARRAY]
                manifest = sweep / ("array-%d.json" % len(arrays))
                write_atomic(manifest, json.dumps({"header": header, "runs": [
                    {"key": r.key, "describe": r.describe, "renderer": r.adapter.name,
                     "scene": str(Path(r.scene.path).resolve()), "params": r.params,
                     "force": self.retry_failed} for r in chunk]}, indent=1) + "\n")
                arrays.append({"manifest": manifest, "runs": chunk, "name": name,
                               "seconds": seconds, "mb": mb, "sweep": sweep})
        return arrays

    def _sbatch(self, args, manifest, sweep):
        cmd = ["sbatch", "--parsable", "--chdir", str(sweep)]
        if self.partition:
            cmd += ["--partition", self.partition]
        if self.account:
            cmd += ["--account", self.account]
        cmd += args + self.sbatch_args + [str(sweep / "task.sh")] + manifest
        job = _slurm(cmd).strip().split(";")[0]
        self.jobs.append(job)
        return job

    def _wait(self, jobs, progress=None):
        """Until none of the jobs is in the queue."""
        last, errors = time.time(), 0
        while True:
            # Not `squeue -j`: it fails on a job Slurm has already purged.
            try:
                out = _slurm(["squeue", "-h", "--me", "-o", "%F"])
                errors = 0
            except SlurmError:
                # A busy controller times out now and then: ten failures
                # in a row (about a minute) end the sweep.
                errors += 1
                if errors >= 10:
                    raise
                time.sleep(5)
                continue
            if not set(out.split()) & set(jobs):
                return
            if progress and time.time() - last > 10:
                progress()
                last = time.time()
            time.sleep(self.poll)

    def _probe(self, sweep, manifest, say):
        say("slurm: probing a node (cache, trees, renderer builds)")
        log = sweep / "logs" / "probe.log"
        job = self._sbatch(["--job-name", "shafts-probe", "--time", "5", "--mem", "512",
                            "--output", str(log)], ["--probe", str(manifest)], sweep)
        self._wait([job])
        if not (sweep / "probe.ok").exists():
            state = task_states(job) or {}
            text = log.read_text().strip() if log.exists() else (
                "(no log: the node could not write %s)" % log)
            raise SlurmError("the probe job %s (%s) failed: a task cannot render this sweep: "
                             "%s" % (job, ", ".join(s for s, _ in state.values()) or "?",
                                     text[-800:]))

    def _render(self, arrays, say):
        """Submits the arrays, waits, resubmits what failed on Slurm's side."""
        pending = [(a, list(range(len(a["runs"]))), 1.0, 1.0) for a in arrays]
        attempt = 0
        while pending:
            attempt += 1
            submitted = []
            for a, idx, tfac, mfac in pending:
                spec = ("%d-%d" % (idx[0], idx[-1]) if idx == list(range(idx[0], idx[-1] + 1))
                        else ",".join(map(str, idx)))
                minutes = int(math.ceil(a["seconds"] * tfac / 60.0))
                job = self._sbatch(
                    ["--job-name", "shafts-%s" % a["name"], "--array",
                     "%s%%%d" % (spec, self.parallel), "--time", str(minutes),
                     "--mem", "%dM" % int(a["mb"] * mfac), "--cpus-per-task", str(self.cpus),
                     "--output", str(a["sweep"] / "logs" / "%A_%a.log")],
                    [str(a["manifest"])], a["sweep"])
                say("slurm: job %s: %s, %d tasks, %d min, %d MB each%s" % (
                    job, a["name"], len(idx), minutes, int(a["mb"] * mfac),
                    "" if attempt == 1 else " (attempt %d)" % attempt))
                submitted.append((a, idx, tfac, mfac, job))
            every = [r.key for a, idx, _, _, _ in submitted for r in (a["runs"][i] for i in idx)]
            self._wait([s[-1] for s in submitted], progress=lambda: say(
                "slurm: %d of %d runs done" % (sum(self._done(k) for k in every), len(every))))
            pending = []
            for a, idx, tfac, mfac, job in submitted:
                states = None
                again, t2, m2 = [], tfac, mfac
                for i in idx:
                    run = a["runs"][i]
                    if self._done(run.key):
                        self.rendered.add(run.key)
                        self.failed.pop(run.key, None)
                        continue
                    if states is None:
                        states = task_states(job)
                    log = a["sweep"] / "logs" / ("%s_%d.log" % (job, i))
                    # A task cancelled before it left the array's pending
                    # record leaves no record of its own.
                    state, code = states.get(i, ("UNKNOWN" if log.exists() else
                                                 "CANCELLED before it started (no record "
                                                 "of it is left)", ""))
                    fatal = code.split(":")[0] in (str(NO_CACHE), str(MISMATCH))
                    why = "Slurm task %s_%d ended %s%s on attempt %d; log %s%s" % (
                        job, i, state, " (exit %s)" % code if code else "", attempt, log,
                        "" if log.exists() else " (none: the task never started)")
                    tail = log.read_text(errors="replace").strip().splitlines()[-1:] \
                        if log.exists() else []
                    if tail:
                        why += ": " + tail[0][-300:]
                    self.failed[run.key] = why
                    say("slurm: %s %s: %s" % (run.describe["scene"], run.describe["label"], why))
                    if not fatal and attempt <= self.retries:
                        again.append(i)
                        t2 = max(t2, tfac * 2 if state == "TIMEOUT" else tfac)
                        m2 = max(m2, mfac * 2 if state == "OUT_OF_MEMORY" else mfac)
                if again:
                    pending.append((a, again, t2, m2))

    def _done(self, key):
        return (self.cache.dir(key) / "result.json").exists()

    def _cancel(self):
        if self.jobs:
            subprocess.run(["scancel"] + self.jobs, check=False,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
