"""Scene -> Blender: File > Import > Shafts scene (.json).

One converter: the import runs the C writer of `scene_export --to blender`
(se_blender.c, through se_export_file in libshafts.so, scene_export/se_run.h)
into a temporary directory and builds the objects from its data with the
same builder the exported script runs (blender_build.build_into). So an
imported scene is the scene Cycles renders in the validation, object for
object: world-space triangle meshes (spheres and cylinders tessellated),
materials as sums of closures, lights in Blender's units, light maps as
shadow-only cards, the medium as a box with a volume material.

A scene beyond what Cycles' single precision holds in its own units and
position (docs/scene_export.md, "Precision") is imported scaled and moved as
the writer chose (scene_export/se_scale.h): the collection's custom
properties shafts_scale, shafts_origin and shafts_axes hold the frame (a
scene point p is at (p - shafts_origin) * shafts_scale, Blender's X, Y, Z
along the scene axes shafts_axes names: "+x -z +y" as in coords.py but for
a far camera looking along a scene axis, which is turned to look down -Z),
and the import's messages say so. A scene of ordinary size near its origin is
imported as it is.

The library is shafts.py's (shafts.load_library: an explicit path, the
environment variable SHAFTS_LIB, libshafts.so next to the package, then the
repository's build/libshafts.so), its errors read through shafts.py's
sh_error accessors.
"""
import ctypes
import json
import os
import re
import shutil
import tempfile

from . import blender_build, phase
from .. import shafts


class ImportFailed(Exception):
    """The scene file or the library refused the import; the message is the
    library's located error (file:line:column: key: message)."""


def blender_data(scene_path, directory, lib_path=None):
    """Runs the C writer on a scene file: writes scene.py, scene.blender.json and
    the light maps into `directory` and returns the data (a dict)."""
    try:
        lib = shafts.load_library(lib_path)
    except OSError as e:
        raise ImportFailed(str(e))
    fn = lib.se_export_file
    fn.restype = ctypes.c_int
    fn.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                   ctypes.c_void_p]
    out = os.path.join(directory, "scene.py")
    with shafts._Error(lib) as err:
        code = fn(os.fsencode(os.path.abspath(scene_path)), b"blender", 0,
                  os.fsencode(out), err.ptr)
        if code != 0:
            raise ImportFailed(str(err.exception(code)))
    with open(os.path.join(directory, "scene.blender.json"), "r", encoding="utf-8") as f:
        return json.load(f)


def import_scene(context, scene_path, lib_path=None):
    """Adds the scene file's objects to a new collection named after it in
    the current scene, makes its camera the scene's camera and sets the
    render size. Returns the import's messages: the writer's notes (what
    Cycles approximates), each phase Cycles cannot hold said with which
    engines render it exactly (phase_messages).
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
        return frame_message(collection, data) + notes(data)
    except blender_build.DataError as e:
        _remove(collection)
        raise ImportFailed(str(e))
    except BaseException:
        _remove(collection)
        raise
    finally:
        shutil.rmtree(work, ignore_errors=True)


# The writer's note on a phase Cycles cannot hold (se_blender.c,
# se_blender_atmo.c): the import says more (phase_messages).
WRITER_PHASE_NOTE = re.compile(r"Cycles has no \S+ phase")


def notes(data):
    """The import's messages on the writer's data: its notes, those on the
    phase replaced by phase_messages, which also say which engines are
    exact."""
    kept = [str(n) for n in data.get("notes", []) if not WRITER_PHASE_NOTE.search(str(n))]
    return phase_messages(data) + kept


def _distinct_lobes(gs):
    """Cycles' phase of Volume Scatter lobes: it merges lobes of equal g and
    sums the rest without their weights (medium.py), an equal-weight
    mixture of the distinct g."""
    distinct = sorted({round(float(g), 6) for g in gs})
    return [(1.0 / len(distinct), g) for g in distinct]


def phase_messages(data):
    """One sentence for each phase of the scene's medium that Cycles cannot
    hold (phase.message): our engines render it exactly (the import
    records it: the material's shafts_medium or shafts_phase), Cycles by
    the lobes in the data, off by as much as phase.largest_error says."""
    item = data.get("medium")
    scene_medium = item.get("scene") if isinstance(item, dict) else None
    if not isinstance(scene_medium, dict):
        return []
    out = []
    if scene_medium.get("type") == "atmosphere":
        atmo = item.get("atmosphere", {})
        parts = [("medium.rayleigh", {"type": "rayleigh"}, 0)]
        if isinstance(scene_medium.get("mie"), dict):
            parts.append(("medium.mie", scene_medium["mie"].get("phase", {}), 1))
        for what, p, part in parts:
            # One lobe chosen per point with these probabilities: exact in
            # expectation, so the mixture's weights are theirs.
            lobes = [(float(s["to"]) - float(s["from"]), float(s["anisotropy"]))
                     for s in atmo.get("scatter", []) if s.get("part") == part]
            if lobes and not phase.exact_in_cycles(p):
                out.append(phase.message(what, p, lobes, atmosphere=True))
        return out
    p = scene_medium.get("phase", {"type": "isotropic"})
    if phase.exact_in_cycles(p):
        return out
    mix = item.get("cycles_mixture")
    if isinstance(mix, dict) and mix.get("scatter"):
        lobes = _distinct_lobes(s["anisotropy"] for s in mix["scatter"])
    else:
        lobes = [(1.0, float(item.get("volume", {}).get("anisotropy", 0.0)))]
    out.append(phase.message("medium", p, lobes))
    return out


# Blender's X, Y, Z as the scene's axes in the writer's usual frame
# (coords.py); a far camera along the scene's axes turns them.
STANDARD_AXES = ["+x", "-z", "+y"]


def frame_message(collection, data):
    """The writer's frame, kept on the collection; a message (in a list) if
    the scene was scaled or moved, else []."""
    frame = data.get("frame", {})
    scale = float(frame.get("scale", 1.0))
    origin = [float(x) for x in frame.get("origin", [0.0, 0.0, 0.0])]
    axes = [str(a) for a in frame.get("axes", STANDARD_AXES)]
    # build_into set the collection's shafts_scale, shafts_origin and
    # shafts_axes (blender_build.set_frame_properties).
    if scale == 1.0 and not any(origin) and axes == STANDARD_AXES:
        return []
    turned = "" if axes == STANDARD_AXES else (
        ", Blender's X, Y and Z along the scene's %s, %s and %s" % tuple(axes))
    return ["the scene is imported with lengths multiplied by %g and its point (%.17g, "
            "%.17g, %.17g) at the origin%s, where Cycles' single precision holds it "
            "(the same image; collection properties shafts_scale, shafts_origin, "
            "shafts_axes)" % (scale, origin[0], origin[1], origin[2], turned)]


def _remove(collection):
    import bpy
    if collection is None:
        return
    for obj in list(collection.objects):
        bpy.data.objects.remove(obj)
    bpy.data.collections.remove(collection)
