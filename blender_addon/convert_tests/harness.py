"""A tiny check harness for the convert tests, run inside Blender:

    blender -b --factory-startup --python TEST.py -- BUILD_DIR

Each test module calls check()/near() and finally finish(), which exits 1
if any check failed (Blender's own exit status is 0 otherwise)."""
import math
import os
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


def finish():
    if _failed:
        print("%d check(s) failed: %s" % (len(_failed), ", ".join(_failed)))
        sys.stdout.flush()
        os._exit(1)
    print("all checks passed")
    sys.stdout.flush()
    os._exit(0)
