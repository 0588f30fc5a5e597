"""What the Slurm executor costs per task, against the local executor.

  python3 -m validation.slurm_bench [--build-dir build] [--runs N] [--spp S] [--size WxH]

Renders N distinct runs (lmm_tracer's reference mode at S spp, seeds 1 to
N, on the hard cases' base scene at a small size) three times into fresh
caches: with the local executor (one at a time, in this process), and with
the Slurm executor on the single-node Slurm of tools/slurm_local.sh, one
task at a time (%1) and as many at once as the node's CPUs allow. Prints
the wall time of each, per run, and the Slurm executor's overhead per run
over the local one, the probe job included (it is one per sweep). Starts
the single-node Slurm with its own state directory and stops it again.
The figures in docs/validation.md come from this script.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from . import renderers, slurm
from .hard import cases as hard_cases
from .runs import LocalExecutor, RunCache, plan_run
from .scenes import prepare_data

HERE = Path(__file__).resolve().parent

ROOT = HERE.parent


def sweep(ctx, cache_dir, n, spp, size):
    cache = RunCache(cache_dir)
    scene = prepare_data("bench", hard_cases.base_scene(*size), HERE, cache.root)
    planned = [plan_run(ctx, renderers.REFERENCE, scene,
                        {"mode": "reference", "spp": spp, "seed": k}, "seed %d" % k)
               for k in range(1, n + 1)]
    return cache, planned


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--runs", type=int, default=12)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--size", default="64x48")
    args = ap.parse_args(argv)
    size = tuple(int(v) for v in args.size.split("x"))
    ctx = renderers.Context(ROOT, args.build_dir, mode="quick", say=lambda m: None)
    if renderers.REFERENCE.missing(ctx):
        print("slurm_bench: build lmm_tracer first (%s)" % ctx.build, file=sys.stderr)
        return 2
    cluster = Path(args.build_dir).resolve() / "slurm-bench-cluster"
    env = dict(os.environ, SHAFTS_SLURM_DIR=str(cluster))
    os.environ["SLURM_CONF"] = str(cluster / "slurm.conf")
    start = subprocess.run([str(ROOT / "tools" / "slurm_local.sh"), "start"], env=env)
    if start.returncode != 0:
        print("slurm_bench: the single-node Slurm cannot start", file=sys.stderr)
        return 1
    rows = []
    try:
        with tempfile.TemporaryDirectory(prefix="slurm_bench.") as tmp:
            cache, planned = sweep(ctx, Path(tmp) / "local", args.runs, args.spp, size)
            local = LocalExecutor(ctx, cache)
            t0 = time.perf_counter()
            renders = sum(local.run(r)["wall_seconds"] for r in planned)
            rows.append(("local, one at a time", time.perf_counter() - t0, renders))
            cpus = os.cpu_count() or 1
            for parallel in (1, cpus):
                cache, planned = sweep(ctx, Path(tmp) / ("slurm%d" % parallel),
                                       args.runs, args.spp, size)
                ex = slurm.SlurmExecutor(ctx, cache, parallel=parallel, retries=0, poll=0.2)
                t0 = time.perf_counter()
                ex.prefetch(planned, say=lambda m: None)
                wall = time.perf_counter() - t0
                results = [cache.load(r.key) for r in planned]
                if ex.failed or any(r is None or r["status"] != "ok" for r in results):
                    print("slurm_bench: a task failed: %s" % json.dumps(ex.failed))
                    return 1
                rows.append(("slurm, %d at a time" % parallel, wall,
                             sum(r["wall_seconds"] for r in results)))
    finally:
        subprocess.run([str(ROOT / "tools" / "slurm_local.sh"), "stop"], env=env)
    n = args.runs
    print("%d runs: lmm_tracer reference, %d spp, %dx%d, on %d CPUs"
          % (n, args.spp, size[0], size[1], os.cpu_count() or 1))
    print("| executor | sweep wall | per run | renders alone | overhead per run vs local |")
    print("|---|---:|---:|---:|---:|")
    for name, wall, renders in rows:
        print("| %s | %.1f s | %.2f s | %.1f s | %+.2f s |" % (
            name, wall, wall / n, renders, (wall - rows[0][1]) / n))
    return 0


if __name__ == "__main__":
    sys.exit(main())
