"""An Export written as files: the scene's JSON with its meshes as binary PLY
files beside it, and the light maps that exist only inside Blender as PFM
files (NAME_map<i>.pfm).

    write_files(export, json_path) -> list of paths written

The meshes go to NAME_mesh<i>.ply in the JSON's directory (NAME the JSON's
base name), little-endian float32 positions and int32 triangles, in the
scene's frame and object space (the shape's transform stays in the JSON);
the core reads them through assimp. Each file is written to a temporary
name and renamed into place; if any write fails, the files this call wrote
are removed and the error raised: an export is written whole or not at all.
"""
import copy
import json
import os

import numpy as np

from . import cards

_FACE = np.dtype([("n", "u1"), ("v", "<i4", (3,))])


def _ply_bytes(positions, indices):
    header = ("ply\nformat binary_little_endian 1.0\n"
              "comment written by the shafts_blender add-on\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(positions), len(indices))).encode("ascii")
    faces = np.empty(len(indices), dtype=_FACE)
    faces["n"] = 3
    faces["v"] = indices
    return header + np.ascontiguousarray(positions, dtype="<f4").tobytes() + faces.tobytes()


def _write_atomic(path, data, written):
    tmp = "%s.tmp%d" % (path, os.getpid())
    try:
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    written.append(path)


def scene_with_files(export, json_path):
    """The export's scene with its in-memory meshes, the light maps it
    holds only in a temporary directory (cards.py) and the images it names
    by absolute paths replaced by the file names write_files gives them; {file name: mesh name}; {file name:
    temporary image path}."""
    base = os.path.splitext(os.path.basename(json_path))[0]
    scene = copy.deepcopy(export.scene)
    names = {}
    for shape in scene["shapes"]:
        data = shape.pop("data", None)
        if data is None:
            continue
        if data not in names:
            names[data] = "%s_mesh%d.ply" % (base, len(names))
        shape["file"] = names[data]
    images = {}
    for light in scene["lights"]:
        lm = light.get("light_map")
        # A scene file names only files in its own tree: the user's images
        # are copied beside it too, in their own format.
        if lm is not None and (cards.is_cached(lm["image"]) or os.path.isabs(lm["image"])):
            ext = ".pfm" if cards.is_cached(lm["image"]) else os.path.splitext(lm["image"])[1]
            name = "%s_map%d%s" % (base, len(images), ext)
            images[name] = lm["image"]
            lm["image"] = name
    return scene, {v: k for k, v in names.items()}, images


def write_files(export, json_path):
    """Writes the scene JSON and its PLY meshes; returns the paths."""
    json_path = os.path.abspath(json_path)
    directory = os.path.dirname(json_path)
    scene, files, images = scene_with_files(export, json_path)
    written = []
    try:
        for name, src in images.items():
            with open(src, "rb") as f:
                _write_atomic(os.path.join(directory, name), f.read(), written)
        for name, data in files.items():
            positions, indices = export.meshes[data]
            _write_atomic(os.path.join(directory, name), _ply_bytes(positions, indices),
                          written)
        _write_atomic(json_path, (json.dumps(scene, indent=1) + "\n").encode("utf-8"),
                      written)
    except BaseException:
        for path in written:
            try:
                os.unlink(path)
            except OSError:
                pass
        raise
    return written
