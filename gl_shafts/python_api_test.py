#!/usr/bin/env python3
"""libshafts.so from Python through ctypes, as the Blender add-on uses it:
a scene parsed from text, rendered by gl_shafts in-process into the
caller's buffer (twice, on one renderer), written as EXR, and compared with
the gl_shafts CLI's image of the same scene; and a bad scene's error read
back with its line and column.

    python_api_test.py LIBSHAFTS GL_SHAFTS SHAFTS_COMPARE SOURCE_DIR
"""
import ctypes
import json
import math
import shutil
import subprocess
import sys
import tempfile
from ctypes import POINTER, byref, c_char, c_char_p, c_double, c_float, c_int, c_void_p
from pathlib import Path


class ShError(ctypes.Structure):
    """core/sh_error.h: sh_error."""
    _fields_ = [("status", c_int), ("file", c_char * 512), ("line", c_int),
                ("column", c_int), ("path", c_char * 256), ("message", c_char * 1024)]


class ShImage(ctypes.Structure):
    """core/sh_image.h: sh_image."""
    _fields_ = [("width", c_int), ("height", c_int), ("rgb", POINTER(c_float))]


def bind(lib):
    sig = {
        "sh_scene_parse": (c_int, [c_char_p, c_char_p, c_char_p, POINTER(c_void_p), POINTER(ShError)]),
        "sh_scene_free": (None, [c_void_p]),
        "sh_scene_image_size": (None, [c_void_p, POINTER(c_int), POINTER(c_int)]),
        "sh_strerror": (c_char_p, [c_int]),
        "sh_image_write": (c_int, [c_char_p, POINTER(ShImage), c_double, POINTER(ShError)]),
        "gs_renderer_create": (c_int, [c_void_p, c_void_p, POINTER(c_void_p), POINTER(ShError)]),
        "gs_renderer_draw": (c_int, [c_void_p, POINTER(c_float), c_void_p, POINTER(ShError)]),
        "gs_renderer_free": (None, [c_void_p]),
    }
    for name, (res, args) in sig.items():
        f = getattr(lib, name)
        f.restype, f.argtypes = res, args


failures = []


def check(cond, what):
    print("%s: %s" % ("ok" if cond else "FAIL", what))
    if not cond:
        failures.append(what)


def main():
    libpath, gl_shafts, compare, source = sys.argv[1:5]
    lib = ctypes.CDLL(str(Path(libpath).resolve()))
    bind(lib)
    scenes = Path(source).resolve() / "scenes"
    data = json.loads((scenes / "teapot_spot.json").read_text())
    data["camera"]["width"], data["camera"]["height"] = 80, 60
    text = json.dumps(data).encode()
    err = ShError()

    scene = c_void_p()
    st = lib.sh_scene_parse(text, b"inline.json", str(scenes).encode(), byref(scene), byref(err))
    check(st == 0, "sh_scene_parse: %s" % err.message.decode(errors="replace"))
    if st != 0:
        return 1
    w, h = c_int(), c_int()
    lib.sh_scene_image_size(scene, byref(w), byref(h))
    check((w.value, h.value) == (80, 60), "sh_scene_image_size: %dx%d" % (w.value, h.value))

    renderer = c_void_p()
    st = lib.gs_renderer_create(scene, None, byref(renderer), byref(err))
    check(st == 0, "gs_renderer_create with the scene's defaults: %s"
          % err.message.decode(errors="replace"))
    if st != 0:
        return 1
    n = w.value * h.value * 3
    first, second = (c_float * n)(), (c_float * n)()
    check(lib.gs_renderer_draw(renderer, first, None, byref(err)) == 0, "first frame")
    check(lib.gs_renderer_draw(renderer, second, None, byref(err)) == 0, "second frame")
    check(list(first) == list(second), "a renderer draws the same frame twice")
    check(all(math.isfinite(v) and v >= 0 for v in first) and max(first) > 0,
          "finite, non-negative, not black")
    lib.gs_renderer_free(renderer)

    with tempfile.TemporaryDirectory() as tmp:
        mine, cli = Path(tmp) / "api.exr", Path(tmp) / "cli.exr"
        img = ShImage(w.value, h.value, ctypes.cast(first, POINTER(c_float)))
        check(lib.sh_image_write(str(mine).encode(), byref(img), 0.0, byref(err)) == 0,
              "sh_image_write")
        scene_file = Path(tmp) / "scene.json"
        scene_file.write_text(json.dumps(data))
        # Relative asset paths resolve against the scene file's directory.
        for asset in (scenes / "assets").iterdir():
            (Path(tmp) / "assets").mkdir(exist_ok=True)
            shutil.copyfile(asset, Path(tmp) / "assets" / asset.name)
        subprocess.run([gl_shafts, str(scene_file), "-o", str(cli), "-q"], check=True)
        r = subprocess.run([compare, str(cli), str(mine), "--max-rel-rms", "1e-6"],
                           stdout=subprocess.PIPE, universal_newlines=True)
        check(r.returncode == 0, "the in-process image equals the CLI's\n" + r.stdout)
    lib.sh_scene_free(scene)

    bad = b'{"format": "shafts-scene", "version": 1,\n "camera": {"fov_y_deg": "wide"}}'
    scene = c_void_p()
    st = lib.sh_scene_parse(bad, b"bad.json", b".", byref(scene), byref(err))
    msg = err.message.decode(errors="replace")
    check(st != 0 and not scene.value, "a bad scene is refused: %s (%s)"
          % (lib.sh_strerror(st).decode(), msg))
    check(err.line == 2 and err.column > 0 and err.file == b"bad.json",
          "its error has a location: %s:%d:%d %s" % (err.file.decode(), err.line, err.column,
                                                     err.path.decode()))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
