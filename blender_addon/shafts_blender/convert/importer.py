"""Scene -> Blender: File > Import > Shafts scene (.json).

One converter: the import runs the C writer of `scene_export --to blender`
(se_blender.c, through se_export_file in libshafts.so, scene_export/se_run.h)
into a temporary directory and builds the objects from its data with the
same builder the exported script runs (blender_build.build_into). So an
imported scene is the scene Cycles renders in the validation, object for
object: world-space triangle meshes (spheres and cylinders tessellated),
materials as sums of closures, lights in Blender's units, light maps as
shadow-only cards, the medium as a box with a volume material.

The library is found as shafts.py finds it: an explicit path, the
environment variable SHAFTS_LIB, libshafts.so next to the package, then the
repository's build/libshafts.so.
"""
import ctypes
import json
import os
import shutil
import tempfile

from . import blender_build

_HERE = os.path.dirname(os.path.abspath(__file__))
_lib = None


class ImportFailed(Exception):
    """The scene file or the library refused the import; the message is the
    library's located error (file:line:column: key: message)."""


def library_path(path=None):
    candidates = [path, os.environ.get("SHAFTS_LIB"),
                  os.path.join(os.path.dirname(_HERE), "libshafts.so"),
                  os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(_HERE))),
                               "build", "libshafts.so")]
    for c in candidates:
        if c and os.path.isfile(c):
            return c
    raise ImportFailed("libshafts.so not found (set SHAFTS_LIB, or build the project)")


def _library(path=None):
    global _lib
    if _lib is None or path is not None:
        lib = ctypes.CDLL(library_path(path))
        lib.se_export_file.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int,
                                       ctypes.c_char_p, ctypes.c_void_p]
        lib.se_export_file.restype = ctypes.c_int
        lib.sh_error_format.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_ulong]
        lib.sh_error_format.restype = None
        _lib = lib
    return _lib


def blender_data(scene_path, directory, lib_path=None):
    """Runs the C writer on a scene file: writes scene.py, scene.json and
    the light maps into `directory` and returns the data (a dict)."""
    lib = _library(lib_path)
    # An sh_error is under 2 kB (core/sh_error.h); the buffer holds it
    # without mirroring its fields, and sh_error_format reads it back.
    err = ctypes.create_string_buffer(16384)
    out = os.path.join(directory, "scene.py")
    status = lib.se_export_file(os.fsencode(os.path.abspath(scene_path)), b"blender", 0,
                                os.fsencode(out), err)
    if status != 0:
        msg = ctypes.create_string_buffer(4096)
        lib.sh_error_format(err, msg, len(msg))
        raise ImportFailed(msg.value.decode("utf-8", "replace"))
    with open(os.path.join(directory, "scene.json"), "r", encoding="utf-8") as f:
        return json.load(f)


def import_scene(context, scene_path, lib_path=None):
    """Adds the scene file's objects to a new collection named after it in
    the current scene, makes its camera the scene's camera and sets the
    render size. Returns the writer's notes (what Cycles approximates).
    On failure nothing is left in the scene and ImportFailed is raised."""
    import bpy
    scene = context.scene
    work = tempfile.mkdtemp(prefix="shafts_import_")
    collection = None
    try:
        data = blender_data(scene_path, work, lib_path)
        name = os.path.splitext(os.path.basename(scene_path))[0] or "shafts scene"
        collection = bpy.data.collections.new(name)
        scene.collection.children.link(collection)
        blender_build.build_into(scene, collection, data, work, "cycles")
        r = data.get("render", {})
        scene.render.resolution_x = int(r.get("width", scene.render.resolution_x))
        scene.render.resolution_y = int(r.get("height", scene.render.resolution_y))
        scene.render.resolution_percentage = 100
        return [str(n) for n in data.get("notes", [])]
    except blender_build.DataError as e:
        _remove(collection)
        raise ImportFailed(str(e))
    except BaseException:
        _remove(collection)
        raise
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _remove(collection):
    import bpy
    if collection is None:
        return
    for obj in list(collection.objects):
        bpy.data.objects.remove(obj)
    bpy.data.collections.remove(collection)
