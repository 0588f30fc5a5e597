"""shafts from Python: scenes, the gl_shafts sweep and the ray tracer
in-process, through ctypes over libshafts.so (docs/api.md).

Needs numpy and nothing from Blender, so it works in any Python 3 as well
as inside Blender. No C struct is mirrored here: scenes, renderers, options
and error reports are opaque handles, options are set by name
(gs_options_set, lmm_render_options_set), statistics come back as JSON, and
images are written by the library into numpy arrays.

    import shafts
    with shafts.Scene.load("scenes/teapot_spot.json") as scene:
        rgb, stats = shafts.SweepRenderer(scene).draw()   # (h, w, 3) float32

The library is found, in order: the `path` given to `load_library`, the
environment variable SHAFTS_LIB, libshafts.so next to this file (the
add-on's zip), the repository's build/libshafts.so.

Threads: every call releases the GIL while the library works. A renderer
is used by one thread at a time; progress callbacks run on the library's
worker threads (keep them cheap); a CancelFlag may be set from any thread.
"""
import ctypes
import json
import os
import threading
import weakref
from ctypes import (CFUNCTYPE, POINTER, byref, c_char_p, c_double,
                    c_int, c_long, c_size_t, c_uint, c_void_p)

import numpy as np

__all__ = ["ShaftsError", "CancelFlag", "Scene", "SweepRenderer", "version",
           "render_reference", "render_lmm", "load_library", "write_image",
           "CHANGED_CAMERA", "CHANGED_LIGHTS", "CHANGED_MEDIUM",
           "CHANGED_SHAPES", "CHANGED_SIZE", "CHANGED_ENVIRONMENT"]

# SH_CHANGED_* of core/shafts.h: the bits Scene.update returns.
CHANGED_CAMERA = 1
CHANGED_LIGHTS = 2
CHANGED_MEDIUM = 4
CHANGED_SHAPES = 8
CHANGED_SIZE = 16
CHANGED_ENVIRONMENT = 32

# sh_status of core/sh_error.h, by name.
_STATUS = {0: "ok", 1: "io", 2: "syntax", 3: "scene", 4: "nomem", 5: "image",
           6: "mesh", 7: "device", 8: "arg", 9: "cancelled"}

_PROGRESS = CFUNCTYPE(None, c_void_p, c_long, c_long)

_HERE = os.path.dirname(os.path.abspath(__file__))
_lib = None
_lib_lock = threading.Lock()


class ShaftsError(Exception):
    """A library error: .status is the status's name ("scene", "io",
    "cancelled", ...), .code its number, and .file, .line, .column and .key
    (the key path, such as "lights[0].intensity") locate it where that is
    known (empty or 0 otherwise); .message is the library's sentence."""

    def __init__(self, code, message, file="", line=0, column=0, key=""):
        self.code = code
        self.status = _STATUS.get(code, "unknown")
        self.message, self.file, self.line, self.column, self.key = (
            message, file, line, column, key)
        where = ""
        if file:
            where = "%s:%d:%d: " % (file, line, column) if line else file + ": "
        if key:
            where += key + ": "
        super().__init__(where + message)


class CancelFlag:
    """The library's cancel flag: pass it to a render, call .set() from any
    thread to stop it (the render raises ShaftsError "cancelled")."""

    def __init__(self):
        self._flag = c_int(0)

    def set(self):
        self._flag.value = 1

    def is_set(self):
        return bool(self._flag.value)

    def clear(self):
        self._flag.value = 0


# The library's functions: name -> (result type, argument types).
_SIGNATURES = {
    "sh_version": (c_char_p, []),
    "sh_strerror": (c_char_p, [c_int]),
    "sh_error_new": (c_void_p, []),
    "sh_error_free": (None, [c_void_p]),
    "sh_error_status": (c_int, [c_void_p]),
    "sh_error_file": (c_char_p, [c_void_p]),
    "sh_error_line": (c_int, [c_void_p]),
    "sh_error_column": (c_int, [c_void_p]),
    "sh_error_key": (c_char_p, [c_void_p]),
    "sh_error_message": (c_char_p, [c_void_p]),
    "sh_scene_load": (c_int, [c_char_p, POINTER(c_void_p), c_void_p]),
    "sh_scene_parse_arrays": (c_int, [c_char_p, c_char_p, c_char_p, c_int,
                                      POINTER(c_char_p), POINTER(c_void_p),
                                      POINTER(c_int), POINTER(c_void_p),
                                      POINTER(c_int), POINTER(c_void_p), c_void_p]),
    "sh_scene_update": (c_int, [c_void_p, c_char_p, c_char_p, POINTER(c_uint),
                                c_void_p]),
    "sh_scene_free": (None, [c_void_p]),
    "sh_scene_image_size": (None, [c_void_p, POINTER(c_int), POINTER(c_int)]),
    "sh_image_write_rgb": (c_int, [c_char_p, c_int, c_int, c_void_p, c_double, c_void_p]),
    "gs_options_new": (c_void_p, [c_void_p]),
    "gs_options_free": (None, [c_void_p]),
    "gs_options_set": (c_int, [c_void_p, c_char_p, c_char_p, c_void_p]),
    "gs_stats_size": (c_size_t, []),
    "gs_stats_json": (c_size_t, [c_void_p, c_char_p, c_size_t]),
    "gs_renderer_create": (c_int, [c_void_p, c_void_p, POINTER(c_void_p), c_void_p]),
    "gs_renderer_draw": (c_int, [c_void_p, c_void_p, c_void_p, c_void_p]),
    "gs_renderer_free": (None, [c_void_p]),
    "lmm_render_options_new": (c_void_p, []),
    "lmm_render_options_free": (None, [c_void_p]),
    "lmm_render_options_set": (c_int, [c_void_p, c_char_p, c_char_p, c_void_p]),
    "lmm_render_options_set_callbacks": (None, [c_void_p, _PROGRESS, c_void_p,
                                                POINTER(c_int)]),
    "lmm_render_stats_size": (c_size_t, []),
    "lmm_render_stats_json": (c_size_t, [c_void_p, c_char_p, c_size_t]),
    "lmm_render": (c_int, [c_void_p, c_void_p, c_void_p, c_void_p, c_void_p]),
}
# Functions that later versions add; bound when the library has them.
_OPTIONAL = {
    "gs_renderer_sync": (c_int, [c_void_p, c_uint, c_void_p]),
}


def library_path(path=None):
    """The libshafts.so that load_library(path) would load."""
    repo = os.path.dirname(os.path.dirname(_HERE))
    candidates = [path, os.environ.get("SHAFTS_LIB"),
                  os.path.join(_HERE, "libshafts.so"),
                  os.path.join(repo, "build", "libshafts.so")]
    for c in candidates:
        if c and os.path.isfile(c):
            return os.path.abspath(c)
    raise OSError("libshafts.so not found: give a path, set SHAFTS_LIB, or "
                  "build the project (cmake --build build)")


def load_library(path=None):
    """Loads and binds libshafts.so once; later calls return the same
    library."""
    global _lib
    with _lib_lock:
        if _lib is None:
            lib = ctypes.CDLL(library_path(path))
            for table, required in ((_SIGNATURES, True), (_OPTIONAL, False)):
                for name, (res, args) in table.items():
                    f = getattr(lib, name, None) if not required else getattr(lib, name)
                    if f is not None:
                        f.restype, f.argtypes = res, args
            _lib = lib
        return _lib


def _text(value):
    return value.decode("utf-8", "replace") if value else ""


class _Error:
    """An sh_error on the heap, read through its accessors."""

    def __init__(self, lib):
        self._lib = lib
        self.ptr = lib.sh_error_new()
        if not self.ptr:
            raise MemoryError("sh_error_new")

    def exception(self, code):
        lib, p = self._lib, self.ptr
        return ShaftsError(code, _text(lib.sh_error_message(p)),
                           _text(lib.sh_error_file(p)), lib.sh_error_line(p),
                           lib.sh_error_column(p), _text(lib.sh_error_key(p)))

    def check(self, code):
        if code != 0:
            raise self.exception(code)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._lib.sh_error_free(self.ptr)
        self.ptr = None


def version():
    """The library's version, "MAJOR.MINOR.PATCH"."""
    return _text(load_library().sh_version())


def write_image(path, rgb, exposure=0.0):
    """Writes a (height, width, 3) float image: ".exr" as 32-bit float
    linear radiance, ".png" as sRGB of radiance * 2^exposure, clamped; the
    file appears complete or not at all."""
    lib = load_library()
    rgb = np.ascontiguousarray(rgb, dtype=np.float32)
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise ValueError("expected a (height, width, 3) array, got %s" % (rgb.shape,))
    with _Error(lib) as err:
        err.check(lib.sh_image_write_rgb(_encode(os.fspath(path)), rgb.shape[1],
                                         rgb.shape[0], rgb.ctypes.data,
                                         float(exposure), err.ptr))


def _encode(s):
    return s.encode("utf-8") if isinstance(s, str) else s


class _Closable:
    """A library handle that close() frees: a context manager, closed when
    collected."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


class Scene(_Closable):
    """A parsed, validated scene (docs/scene-format.md). Renderers made
    from it must not outlive it: close() closes them first."""

    def __init__(self, handle, lib):
        self._handle = c_void_p(handle)
        self._lib = lib
        self._renderers = weakref.WeakSet()

    @classmethod
    def from_json(cls, text, name="scene.json", base_dir=".", meshes=None):
        """Parses scene text; relative file names resolve against base_dir.
        meshes: {name: (positions, indices)}, float32-compatible (n, 3)
        positions and int32-compatible (m, 3) indices, for mesh shapes
        written {"type": "mesh", "data": name}; the library copies them."""
        lib = load_library()
        if not isinstance(text, (str, bytes)):
            text = json.dumps(text)
        meshes = meshes or {}
        n = len(meshes)
        keep = []  # the arrays must live until the call returns
        names = (c_char_p * max(n, 1))()
        pos = (c_void_p * max(n, 1))()
        idx = (c_void_p * max(n, 1))()
        nv = (c_int * max(n, 1))()
        nt = (c_int * max(n, 1))()
        for i, (mname, (p, t)) in enumerate(meshes.items()):
            p = np.ascontiguousarray(p, dtype=np.float32).reshape(-1, 3)
            t = np.ascontiguousarray(t, dtype=np.int32).reshape(-1, 3)
            keep += [p, t]
            names[i] = _encode(mname)
            pos[i], idx[i] = p.ctypes.data, t.ctypes.data
            nv[i], nt[i] = p.shape[0], t.shape[0]
        out = c_void_p()
        with _Error(lib) as err:
            err.check(lib.sh_scene_parse_arrays(
                _encode(text), _encode(name), _encode(str(base_dir)), n, names,
                pos, nv, idx, nt, byref(out), err.ptr))
        return cls(out.value, lib)

    @classmethod
    def load(cls, path):
        """Loads a scene file; relative names resolve against its folder."""
        lib = load_library()
        out = c_void_p()
        with _Error(lib) as err:
            err.check(lib.sh_scene_load(_encode(os.fspath(path)), byref(out), err.ptr))
        return cls(out.value, lib)

    @property
    def handle(self):
        if not self._handle.value:
            raise ValueError("the scene is closed")
        return self._handle

    @property
    def image_size(self):
        """(width, height) in pixels."""
        w, h = c_int(), c_int()
        self._lib.sh_scene_image_size(self.handle, byref(w), byref(h))
        return w.value, h.value

    def update(self, patch, name="patch.json"):
        """Applies a patch (a dict or JSON text with any of camera, lights,
        medium, background, ambient, transforms; docs/scene-format.md) and
        returns the CHANGED_* bits. A bad patch raises ShaftsError located
        in the patch text and changes nothing."""
        if not isinstance(patch, (str, bytes)):
            patch = json.dumps(patch)
        changed = c_uint(0)
        with _Error(self._lib) as err:
            err.check(self._lib.sh_scene_update(self.handle, _encode(patch),
                                                _encode(name), byref(changed), err.ptr))
        return changed.value

    def close(self):
        if self._handle.value:
            for r in list(self._renderers):
                r.close()
            self._lib.sh_scene_free(self._handle)
            self._handle = c_void_p()


def _stats(fn, buf):
    n = fn(buf, None, 0)
    text = ctypes.create_string_buffer(n + 1)
    fn(buf, text, n + 1)
    return json.loads(text.value.decode("utf-8")) if n else {}


def _value(v):
    if isinstance(v, bool):
        return "1" if v else "0"
    return str(v)


class SweepRenderer(_Closable):
    """gl_shafts (gl_shafts/gs_render.h) on a scene: a GL context with the
    scene uploaded. options: {gs_options field: value} ("planes",
    "lattice_u", "xi", ...); live: values as uniforms, so that sync() after
    Scene.update compiles nothing; backend: "auto", "egl" or "osmesa"."""

    def __init__(self, scene, options=None, live=False, backend="auto"):
        lib = scene._lib
        self._lib, self._scene = lib, scene
        self._handle = c_void_p()
        opt = lib.gs_options_new(scene.handle)
        if not opt:
            raise MemoryError("gs_options_new")
        try:
            with _Error(lib) as err:
                settings = dict(options or {})
                settings.setdefault("backend", backend)
                if live:
                    settings["live"] = 1
                for key, value in settings.items():
                    err.check(lib.gs_options_set(opt, _encode(key),
                                                 _encode(_value(value)), err.ptr))
                err.check(lib.gs_renderer_create(scene.handle, opt,
                                                 byref(self._handle), err.ptr))
        finally:
            lib.gs_options_free(opt)
        self._stats = ctypes.create_string_buffer(lib.gs_stats_size())
        scene._renderers.add(self)

    def draw(self):
        """One frame: (rgb, stats), rgb a float32 (height, width, 3) array
        of linear radiance, rows from the top; stats a dict of gs_stats."""
        if not self._handle.value:
            raise ValueError("the renderer is closed")
        w, h = self._scene.image_size
        rgb = np.empty((h, w, 3), dtype=np.float32)
        with _Error(self._lib) as err:
            err.check(self._lib.gs_renderer_draw(self._handle, rgb.ctypes.data,
                                                 self._stats, err.ptr))
        return rgb, _stats(self._lib.gs_stats_json, self._stats)

    def sync(self, changed):
        """Takes in the scene's changes (the bits Scene.update returned)."""
        fn = getattr(self._lib, "gs_renderer_sync", None)
        if fn is None:
            raise ShaftsError(8, "this libshafts.so has no gs_renderer_sync")
        with _Error(self._lib) as err:
            err.check(fn(self._handle, c_uint(changed), err.ptr))

    def close(self):
        if self._handle.value:
            self._lib.gs_renderer_free(self._handle)
            self._handle = c_void_p()


def _render(scene, settings, progress, cancel):
    """lmm_render (lmm_tracer/lmm_render.h) with options by name."""
    lib = scene._lib
    opt = lib.lmm_render_options_new()
    if not opt:
        raise MemoryError("lmm_render_options_new")
    # The callback object must live as long as the render.
    callback = _PROGRESS(lambda user, done, total: progress(done, total)) \
        if progress else _PROGRESS()
    flag = cancel._flag if cancel is not None else None
    try:
        with _Error(lib) as err:
            for key, value in settings.items():
                if value is not None:
                    err.check(lib.lmm_render_options_set(opt, _encode(key),
                                                         _encode(_value(value)), err.ptr))
            lib.lmm_render_options_set_callbacks(
                opt, callback, None, byref(flag) if flag is not None else None)
            w, h = scene.image_size
            rgb = np.empty((h, w, 3), dtype=np.float32)
            stats = ctypes.create_string_buffer(lib.lmm_render_stats_size())
            err.check(lib.lmm_render(scene.handle, opt, rgb.ctypes.data, stats, err.ptr))
        return rgb, _stats(lib.lmm_render_stats_json, stats)
    finally:
        lib.lmm_render_options_free(opt)


def render_reference(scene, spp=None, threads=0, seed=None, max_depth=None,
                     progress=None, cancel=None):
    """The reference renderer (the ground truth): (rgb, stats). None takes
    the scene's render settings. progress(done, total) is called from the
    worker threads; cancel is a CancelFlag."""
    return _render(scene, {"mode": "reference", "spp": spp, "threads": threads,
                           "seed": seed, "max_depth": max_depth}, progress, cancel)


def render_lmm(scene, mode="lmm", scheme=None, refined=False, mesh_step=None,
               radius=None, volume="mesh", spp=None, threads=0, seed=None,
               max_depth=None, local=False, caustic_rays=None,
               area_radius=None, area_samples=None, progress=None, cancel=None):
    """The light meshes method (mode "lmm") or the Whitted baseline (mode
    "whitted"): (rgb, stats). scheme: "straight", "refract-trace" or
    "refract-both" (None: the scene's); refined: refract-both's refined
    variant; mesh_step: h in scene units; radius: the interpolation radius
    in steps (r = h * radius, the kl of lmm_tracer); volume: "mesh" or
    "exact"; area_radius, area_samples: whitted's sphere lights."""
    settings = {"mode": mode, "scheme": scheme, "refined": refined or None,
                "mesh_step": mesh_step, "kl": radius, "spp": spp,
                "threads": threads, "seed": seed, "max_depth": max_depth,
                "local": local or None, "caustic_rays": caustic_rays,
                "area_radius": area_radius, "area_samples": area_samples}
    if mode == "lmm":
        settings["volume"] = volume
    return _render(scene, settings, progress, cancel)
