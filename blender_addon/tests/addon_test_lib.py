"""What the add-on's tests share, inside Blender (run_blender_test.sh starts
them): installing the zip, checks that count failures, skipping while a part
of the add-on is missing, F12 renders saved as 32-bit EXR."""
import os
import sys
import zipfile
from pathlib import Path

import addon_utils
import bpy

ZIP = Path(os.environ["SHAFTS_ADDON_ZIP"])
BUILD = Path(os.environ.get("SHAFTS_BUILD", ZIP.parent))
SCRATCH = Path(os.environ.get("SHAFTS_SCRATCH", "/tmp"))
SKIP = 77
failures = []


def check(cond, what):
    print("%s: %s" % ("ok" if cond else "FAIL", what), flush=True)
    if not cond:
        failures.append(what)
    return cond


def finish():
    if failures:
        print("%d check(s) failed:\n  %s" % (len(failures), "\n  ".join(failures)))
        sys.exit(1)
    print("all checks passed")
    sys.exit(0)


def skip(why):
    print("SKIP: " + why, flush=True)
    sys.exit(SKIP)


def install(via_preferences=False):
    """Installs the zip as a user would (Preferences > Add-ons > Install, or
    unpacked into the user scripts' addons folder) and enables it."""
    if via_preferences:
        result = bpy.ops.preferences.addon_install(filepath=str(ZIP))
        if result != {'FINISHED'}:
            raise RuntimeError("addon_install: %s" % result)
    else:
        with zipfile.ZipFile(ZIP) as z:
            z.extractall(bpy.utils.user_resource('SCRIPTS', path="addons"))
    addon_utils.modules_refresh()
    module = addon_utils.enable("shafts_blender", default_set=True, handle_error=_raise)
    if module is None:
        raise RuntimeError("addon_utils.enable returned None")
    return module


def _raise(exc):
    raise exc


def require(*names):
    """Skips (exit 77) while a module of the package is not there yet."""
    import importlib
    for name in names:
        try:
            importlib.import_module("shafts_blender." + name)
        except ImportError as e:
            skip("shafts_blender.%s is not available yet (%s)" % (name, e))
