"""The Slurm executor end to end, on a single-node Slurm of its own.

Starts tools/slurm_local.sh (its own state directory and ports), renders a
small sweep (two scenes: a spot in a medium and the same without the
medium; lmm_tracer and gl_shafts at their quick settings; 32x24 images)
with the local executor, then with the Slurm one while one task is
cancelled before it starts and again when it is retried (the jobs are
submitted held so that this is not a race) and a running task is killed
where the test catches one, checks that the sweep reports the killed tasks
with their Slurm state and log, then runs the sweep again and checks that
it renders only the missing runs, and that every image and every
figure equals the local executor's (the renderers are deterministic: pixel
values compared exactly with idiff). Stops Slurm in any case. Where Slurm
cannot start, the test fails with slurm_local.sh's reason.

Run by CTest (validation.slurm_executor) with SHAFTS_SOURCE_DIR and
SHAFTS_BINARY_DIR set.
"""

import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .hard import cases as hard_cases

HERE = Path(__file__).resolve().parent

ROOT = Path(os.environ.get("SHAFTS_SOURCE_DIR", HERE.parent))
BUILD = Path(os.environ.get("SHAFTS_BINARY_DIR", ROOT / "build"))
CLUSTER = BUILD / "slurm-test-cluster"
ENV = dict(os.environ, SHAFTS_SLURM_DIR=str(CLUSTER), PYTHONPATH=str(HERE.parent),
           SLURM_CONF=str(CLUSTER / "slurm.conf"))
failures = []


def check(ok, what):
    print("%s: %s" % ("ok" if ok else "FAIL", what), flush=True)
    if not ok:
        failures.append(what)
    return ok


def slurm_local(cmd):
    return subprocess.run([str(ROOT / "tools" / "slurm_local.sh"), cmd], env=ENV,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def validate(tmp, name, *extra):
    return [sys.executable, "-m", "validation.validate", "--quick", "--report", str(tmp / name),
            "--build-dir", str(BUILD), "--scenes", str(tmp / "spot_medium.json"),
            str(tmp / "spot_clear.json"), "--renderers", "lmm_tracer,gl_shafts",
            "--ref-spp", "16", "--scale", "1", "--no-hard-cases"] + list(extra)


def queue():
    """(array job id, job id as squeue prints it, name, state, reason) of
    every job."""
    out = subprocess.run(["squeue", "-h", "-o", "%F|%i|%j|%T|%r"], env=ENV, text=True,
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL).stdout
    return [tuple(line.split("|")) for line in out.splitlines() if line.count("|") == 4]


def scontrol(*args):
    subprocess.run(["scontrol"] + list(args), env=ENV, check=False,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def scancel(job):
    subprocess.run(["scancel", job], env=ENV, check=False)


def sweep_with_killed_tasks(tmp):
    """The Slurm sweep, every job submitted held so that the test can step
    in: it cancels the last task of the lmm_tracer array before releasing
    it (that task never starts), kills the first gl_shafts task it sees
    running (a render stopped half-way, when the test is quick enough to
    catch it: the run may end first), and cancels every retry the executor
    submits. Returns (status, output, lmm_tracer's job ids, the index of
    its cancelled task)."""
    cmd = validate(tmp, "slurm", "--executor", "slurm", "--cache-dir", str(tmp / "cache-slurm"),
                   "--slurm-parallel", "1", "--slurm-retries", "1", "--sbatch-arg=--hold")
    log = tmp / "slurm-sweep.log"
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, env=ENV, stdout=out, stderr=subprocess.STDOUT)
        seen, names, lmm_jobs, victim, gl_job, killed = set(), set(), [], None, None, None
        while proc.poll() is None:
            for array, jid, name, state, reason in queue():
                if array == gl_job and killed is None and state == "RUNNING":
                    killed = jid
                    scancel(jid)
                if array in seen or "Held" not in reason:
                    continue
                seen.add(array)
                if name in names and name != "shafts-probe":
                    scancel(array)                      # a retry
                elif name == "shafts-lmm_tracer":
                    victim = max(int(i) for i in re.findall(r"\d+", jid.split("_", 1)[1])[:2])
                    scontrol("release", array)
                    scancel("%s_%d" % (array, victim))  # pending: never starts
                else:
                    if name == "shafts-gl_shafts":
                        gl_job = array
                    scontrol("release", array)
                names.add(name)
                if name == "shafts-lmm_tracer":
                    lmm_jobs.append(array)
            time.sleep(0.05)
    print("the test killed running task %s" % killed if killed else
          "no gl_shafts task was seen running (each ended first)")
    return proc.returncode, log.read_text(), lmm_jobs, victim


def runs_by_label(results):
    return {(s["name"], r["renderer"], r["label"]): r for s in results["scenes"]
            for r in s["runs"]}


def main():
    start = slurm_local("start")
    print(start.stdout, end="")
    if start.returncode != 0:
        print("FAIL: the single-node Slurm cannot start (tools/slurm_local.sh start exited "
              "%d): %s" % (start.returncode, start.stdout.strip().splitlines()[-1:]))
        slurm_local("stop")
        return 1
    try:
        with tempfile.TemporaryDirectory(prefix="slurm_test.") as tmp:
            run_checks(Path(tmp))
    finally:
        stop = slurm_local("stop")
        print(stop.stdout, end="")
        left = [p for p in ("munged.pid", "slurmctld.pid", "slurmd.pid")
                if (CLUSTER / p).exists()]
        check(stop.returncode == 0 and not left, "slurm_local.sh stop leaves nothing running")
    print("%d failed checks" % len(failures))
    return 1 if failures else 0


def run_checks(tmp):
    medium = hard_cases.base_scene(32, 24)
    clear = {k: v for k, v in medium.items() if k != "medium"}
    (tmp / "spot_medium.json").write_text(json.dumps(medium))
    (tmp / "spot_clear.json").write_text(json.dumps(clear))

    t0 = time.time()
    local = subprocess.run(validate(tmp, "local", "--cache-dir", str(tmp / "cache-local"), "-q"),
                           env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if not check(local.returncode == 0, "the local sweep (%.0f s)" % (time.time() - t0)):
        print(local.stdout)
        return
    t0 = time.time()
    status, out, lmm_jobs, victim = sweep_with_killed_tasks(tmp)
    print(out)
    check(status == 1, "the Slurm sweep with killed tasks exits with 1 (%d, %.0f s)"
          % (status, time.time() - t0))
    check(len(lmm_jobs) == 2, "the cancelled lmm_tracer task was retried once (jobs %s)"
          % lmm_jobs)
    check(re.search(r"Slurm task %s_%s ended CANCELLED .* on attempt 2; log "
                    % (lmm_jobs[-1] if lmm_jobs else "?", victim), out) is not None,
          "the sweep reports the cancelled task's state, attempt and log")
    slurm1 = json.loads((tmp / "slurm" / "results.json").read_text())
    failed = [r for r in runs_by_label(slurm1).values() if r["status"] != "ok"]
    check(1 <= len(failed) <= 2 and all("CANCELLED" in (r["error"] or "") for r in failed),
          "the report shows the killed runs failed with their Slurm state (%d)" % len(failed))

    t0 = time.time()
    again = subprocess.run(validate(tmp, "slurm", "--executor", "slurm", "--cache-dir",
                                    str(tmp / "cache-slurm")),
                           env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(again.stdout)
    check(again.returncode == 0, "the resumed Slurm sweep (%.0f s)" % (time.time() - t0))
    slurm2 = json.loads((tmp / "slurm" / "results.json").read_text())
    local_r = json.loads((tmp / "local" / "results.json").read_text())
    check(slurm2["executor"]["tasks"] == len(failed) and slurm2["rendered"] == len(failed),
          "the resumed sweep rendered only the %d missing runs (%s tasks, %s rendered)"
          % (len(failed), slurm2["executor"]["tasks"], slurm2["rendered"]))

    a, b = runs_by_label(local_r), runs_by_label(slurm2)
    check(sorted(a) == sorted(b) and len(a) == 13, "the same %d runs" % len(a))
    for k in a:
        if k in b:
            same = all(a[k].get(f) == b[k].get(f) for f in ("status", "metrics", "params"))
            check(same, "%s %s %s: the same status and figures" % k)
    images = sorted((tmp / "cache-local" / "runs").glob("*/*/image.exr"))
    for img in images:
        other = tmp / "cache-slurm" / img.relative_to(tmp / "cache-local")
        d = subprocess.run(["idiff", "-fail", "0", "-warn", "0", str(img), str(other)],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(d.returncode == 0, "run %s: the image is the same, pixel for pixel"
              % img.parent.name[:12])
    check(len(images) == 15, "%d images (13 runs and 2 references)" % len(images))


if __name__ == "__main__":
    sys.exit(main())
