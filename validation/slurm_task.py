"""What one task of the Slurm executor's job arrays runs (slurm.py).

  python3 -m validation.slurm_task MANIFEST          render the run at index
                                                    $SLURM_ARRAY_TASK_ID
  python3 -m validation.slurm_task --probe MANIFEST  check what every task
                                                    needs, on this node

(with the source tree that holds validation/ on PYTHONPATH, as the
executor's task.sh sets it)

A manifest (written by the executor into CACHE/slurm/SWEEP/) holds the
sweep's header (source tree, build tree, mode, timeout, cache directory,
the version of every renderer of the sweep as the submitting machine saw
it) and a list of runs (key, description, renderer, derived scene, settings).
The task renders its run exactly as the local executor does: runs.execute
into the shared run cache, result.json written last and atomically. So a
task killed half-way leaves nothing the cache counts, and a renderer's own
failure is a cached result like any other.

Exit status: 0 when the run's result is in the cache (a failed render is a
result too); 3 when this node cannot read the manifest or the scene, or
cannot write the cache (the cache must be on a file system every node
shares: --cache-dir); 4 when this node's renderer is missing or differs
from the submitting machine's (another build would be cached under the
wrong key); 2 for bad usage. The probe writes probe.ok beside the manifest.
"""

import json
import os
import socket
import sys
from pathlib import Path

from . import renderers
from .runs import RunCache, execute

NO_CACHE, MISMATCH = 3, 4


def fail(status, message):
    print("slurm_task on %s: %s" % (socket.gethostname(), message), file=sys.stderr, flush=True)
    sys.exit(status)


def load(manifest_path):
    """The manifest, the renderers' context and the cache; exits with
    status 3 if this node cannot see or write them."""
    try:
        manifest = json.loads(Path(manifest_path).read_text())
    except (OSError, ValueError) as e:
        fail(NO_CACHE, "cannot read the sweep's manifest %s: %s. The run cache must be "
             "a directory every node sees at the same path (--cache-dir)" % (manifest_path, e))
    head = manifest["header"]
    cache = Path(head["cache"])
    probe = cache / "slurm" / (".probe-%s-%d" % (socket.gethostname(), os.getpid()))
    try:
        probe.write_text("ok\n")
        probe.unlink()
    except OSError as e:
        fail(NO_CACHE, "cannot write the run cache %s: %s" % (cache, e))
    ctx = renderers.Context(head["root"], head["build"], mode=head["mode"],
                            timeout=head["timeout"], say=print,
                            warm_frames=head.get("warm_frames", 0))
    return manifest, ctx, RunCache(cache)


def check_renderer(ctx, name, version):
    """Exits with status 4 unless this node has the renderer at the version
    the submitting machine saw."""
    adapter = renderers.by_name(name)[0]
    note = adapter.missing(ctx)
    if note:
        fail(MISMATCH, "%s cannot run here: %s" % (name, note))
    mine = adapter.version(ctx)
    if mine != version:
        fail(MISMATCH, "%s here is %s, the submitting machine's is %s: the nodes must "
             "run the same build (a shared build tree)" % (name, mine, version))
    return adapter


def probe(manifest_path):
    manifest, ctx, _ = load(manifest_path)
    for name, version in sorted(manifest["header"]["versions"].items()):
        check_renderer(ctx, name, version)
    for run in manifest["runs"]:
        if not Path(run["scene"]).is_file():
            fail(NO_CACHE, "cannot see the scene %s" % run["scene"])
    ok = Path(manifest_path).with_name("probe.ok")
    ok.write_text(socket.gethostname() + "\n")
    print("probe: %s sees the cache and runs the same renderers" % socket.gethostname())
    return 0


def task(manifest_path, index):
    manifest, ctx, cache = load(manifest_path)
    try:
        run = manifest["runs"][index]
    except IndexError:
        fail(2, "no run %d in %s" % (index, manifest_path))
    adapter = check_renderer(ctx, run["renderer"], manifest["header"]["versions"][run["renderer"]])
    scene = Path(run["scene"])
    if not scene.is_file():
        fail(NO_CACHE, "cannot see the scene %s" % scene)
    print("task %d on %s: %s %s, run %s" % (index, socket.gethostname(), run["renderer"],
                                           run["describe"].get("label"), run["key"]), flush=True)
    result = execute(cache, run["key"], run["describe"],
                     lambda work, log: adapter.render(ctx, scene, run["params"], work, log),
                     retry_failed=run["force"], say=print)
    print("%s%s" % (result["status"], ": %s" % result["error"] if result.get("error") else ""))
    return 0


def main(argv):
    if len(argv) == 2 and argv[0] == "--probe":
        return probe(argv[1])
    if len(argv) != 1 or "SLURM_ARRAY_TASK_ID" not in os.environ:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    return task(argv[0], int(os.environ["SLURM_ARRAY_TASK_ID"]))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
