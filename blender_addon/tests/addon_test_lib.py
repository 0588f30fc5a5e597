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


def tool(*parts):
    """A program of the build, e.g. tool("gl_shafts", "gl_shafts")."""
    return str(BUILD.joinpath(*parts))


def run(*argv):
    """Runs a program of the build; raises with its output if it fails."""
    import subprocess
    r = subprocess.run([str(a) for a in argv], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True)
    if r.returncode != 0:
        raise RuntimeError("%s exited with %d:\n%s" % (argv[0], r.returncode, r.stdout))
    return r.stdout


def f12(scene, path):
    """F12 with write_still into a 32-bit float EXR of linear radiance;
    returns the operator's result. The display transform does not touch an
    EXR; Standard is set anyway, as a user comparing numbers would. An
    ERROR report makes the operator raise: its message is returned then."""
    render = scene.render
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    render.image_settings.color_mode = "RGB"
    render.use_file_extension = False
    render.dither_intensity = 0.0
    render.use_compositing = False
    render.use_sequencer = False
    scene.view_settings.view_transform = "Standard"
    render.filepath = str(path)
    try:
        return bpy.ops.render.render(write_still=True)
    except RuntimeError as e:
        return str(e)


def compare(reference, image, diff=None):
    """shafts_compare's figures (rel_rms over the lit pixels, max_abs...);
    diff: the difference image it writes (kept for a failed check)."""
    import json
    argv = [tool("validation", "shafts_compare"), reference, image, "--json"]
    if diff is not None:
        argv += ["--diff", diff]
    return json.loads(run(*argv))


def export_files(scene, json_path, size=None):
    """The scene as convert exports it for F12, written as files (the JSON
    and its meshes) for the command-line renderers; the Export."""
    from shafts_blender import convert
    from shafts_blender.convert.files import write_files
    depsgraph = bpy.context.evaluated_depsgraph_get()
    r = scene.render
    size = size or (r.resolution_x * r.resolution_percentage // 100,
                    r.resolution_y * r.resolution_percentage // 100)
    exported = convert.export_scene(depsgraph, size=size)
    write_files(exported, str(json_path))
    return exported


class captured_stdout:
    """Captures what Blender prints on file descriptor 1 (reports in
    background mode) into ``.text``."""

    def __enter__(self):
        import tempfile
        sys.stdout.flush()
        self._file = tempfile.TemporaryFile(mode="w+")
        self._saved = os.dup(1)
        os.dup2(self._file.fileno(), 1)
        return self

    def __exit__(self, *exc):
        sys.stdout.flush()
        os.dup2(self._saved, 1)
        os.close(self._saved)
        self._file.seek(0)
        self.text = self._file.read()
        self._file.close()
        print(self.text, end="")
        return False


def exr_sum(path):
    """The sum of an image's RGB values (read through Blender)."""
    import numpy as np
    image = bpy.data.images.load(str(path))
    try:
        pixels = np.empty(len(image.pixels), dtype=np.float32)
        image.pixels.foreach_get(pixels)
        return float(pixels.reshape(-1, 4)[:, :3].sum())
    finally:
        bpy.data.images.remove(image)
