"""A tiny check harness for the convert tests, run inside Blender:

    blender -b --factory-startup --python TEST.py -- BUILD_DIR

Each test module calls check()/near() and finally finish(), which exits 1
if any check failed (Blender's own exit status is 0 otherwise)."""
import json
import shutil
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))  # blender_addon/: the package
sys.path.insert(0, HERE)

_failed = []


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return argv


def build_dir():
    a = args()
    return os.path.abspath(a[0]) if a else os.path.join(os.path.dirname(os.path.dirname(HERE)),
                                                        "build")


def check(what, ok, detail=""):
    print("%s: %s%s" % ("ok" if ok else "FAIL", what, (" (%s)" % detail) if detail else ""))
    if not ok:
        _failed.append(what)


def near(what, got, want, tol=1e-5):
    """Relative closeness of numbers or sequences of numbers."""
    g = list(got) if isinstance(got, (list, tuple)) else [got]
    w = list(want) if isinstance(want, (list, tuple)) else [want]
    ok = len(g) == len(w) and all(
        math.isfinite(a) and abs(a - b) <= tol * max(1.0, abs(b)) for a, b in zip(g, w))
    check(what, ok, "got %s, want %s" % (got, want))


def has_warning(what, warnings, *words):
    hit = [w for w in warnings if all(x in w for x in words)]
    check(what, bool(hit), "warnings: %s" % warnings)


def scene_copy(path, work, size):
    """A copy of a scene file in `work` rendered at `size` (w, h), with
    copies of the files it names beside it (a scene names only files in its
    own tree)."""
    with open(path) as f:
        scene = json.load(f)
    scene["camera"]["width"], scene["camera"]["height"] = size
    base = os.path.dirname(os.path.abspath(path))
    for item in scene.get("shapes", []) + scene.get("lights", []):
        for holder in (item, item.get("light_map", {})):
            for key in ("file", "image"):
                if key in holder:
                    src = os.path.join(base, holder[key])
                    holder[key] = os.path.basename(src)
                    shutil.copyfile(src, os.path.join(work, holder[key]))
    out = os.path.join(work, os.path.basename(path))
    with open(out, "w") as f:
        json.dump(scene, f)
    return out


def render_radiance(build, scene_path, exr):
    """lmm_tracer's reference image of a scene file (16 samples, seed 1),
    as the mean of R, G, B per pixel."""
    import bpy
    import numpy as np
    r = subprocess.run([os.path.join(build, "lmm_tracer", "lmm_tracer"), scene_path,
                        "-o", exr, "--spp", "16", "--seed", "1"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("lmm_tracer failed on %s: %s" % (scene_path, r.stderr.strip()))
    img = bpy.data.images.load(exr)
    px = np.empty(len(img.pixels), dtype=np.float32)
    img.pixels.foreach_get(px)
    return px.reshape(-1, 4)[:, :3].mean(axis=1)


def render_difference(build, a_path, b_path, work):
    """(mean relative difference over the lit pixels of a, ratio of the
    sums) of the reference images of two scene files; lit: above 1% of a's
    largest value."""
    import numpy as np
    a = render_radiance(build, a_path, os.path.join(work, "a.exr"))
    b = render_radiance(build, b_path, os.path.join(work, "b.exr"))
    lit = a > 0.01 * a.max()
    return (float(np.mean(np.abs(b[lit] - a[lit]) / a[lit])),
            float(b[lit].sum() / a[lit].sum()))


def finish():
    if _failed:
        print("%d check(s) failed: %s" % (len(_failed), ", ".join(_failed)))
        sys.stdout.flush()
        os._exit(1)
    print("all checks passed")
    sys.stdout.flush()
    os._exit(0)
