"""Scenes as the validation renders them.

A canonical scene is rendered at a size the validation mode chooses, so the
orchestrator writes a derived copy of it into the cache: the same scene with
the camera's width and height changed, in a directory of its own beside
copies of every file it names (a scene names only files in its own tree,
docs/scene-format.md "Files"). The copy is identified by a content
key: a hash of the scene file's bytes, of the bytes of every file it
references (meshes, heightfields, light maps) and of the changes made, so a
run is redone when any of them changes and never because the tree was
cloned somewhere else.
"""

import hashlib
import json
import math
import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path

# Keys whose string values name files relative to the scene file
# (docs/scene-format.md, "Files").
FILE_KEYS = ("file", "image")


@dataclass
class PreparedScene:
    """A scene ready to render: the derived file and what the report needs."""

    name: str
    source: str          # the file the user named (for the report)
    path: Path           # the derived scene file every renderer reads
    key: str             # content hash, part of every run's cache key
    width: int
    height: int
    has_medium: bool
    exposure: float      # render.exposure: the previews' exposure
    # medium.type: "homogeneous", "height_fog", "atmosphere"; None without
    # a medium. The sweeps of some renderers depend on it (renderers.py).
    medium_type: str = None
    data: dict = field(repr=False, default_factory=dict)
    notes: list = field(default_factory=list)


def referenced_files(data, base_dir):
    """Every file the scene names, as (key path, absolute Path), in the order
    they appear. Only `file` and `image` values are file names."""
    found = []

    def walk(node, where):
        if isinstance(node, dict):
            for k, v in node.items():
                here = "%s.%s" % (where, k) if where else k
                if k in FILE_KEYS and isinstance(v, str):
                    found.append((here, (Path(base_dir) / v).resolve()))
                else:
                    walk(v, here)
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, "%s[%d]" % (where, i))

    walk(data, "")
    return found


def mesh_companions(path):
    """The relative names of the files a mesh names in turn: an OBJ's
    material libraries, a glTF's buffer and image URIs (not data: URIs)."""
    try:
        if path.suffix.lower() == ".obj":
            return [line.split(None, 1)[1].strip()
                    for line in path.read_text(errors="replace").splitlines()
                    if line.startswith("mtllib ") and len(line.split(None, 1)) == 2]
        if path.suffix.lower() == ".gltf":
            doc = json.loads(path.read_text())
            return [x["uri"] for k in ("buffers", "images") for x in doc.get(k, [])
                    if isinstance(x.get("uri"), str) and not x["uri"].startswith("data:")]
    except (OSError, ValueError, AttributeError, TypeError):
        pass
    return []


def _place(src, dest):
    """Hard-links src to dest (a copy across file systems)."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    try:
        os.link(src, dest)
    except OSError:
        shutil.copyfile(src, dest)


def localise(data, base_dir, dest_dir, copy=True):
    """A copy of the scene whose file names are relative and lie in
    dest_dir: each referenced file (and the files a mesh names in turn) is
    linked into dest_dir/f<i>/ (names only, without copy). A missing file
    keeps a name that does not exist there, so the renderers report it."""
    count = [0]

    def place(name):
        src = (Path(base_dir) / name).resolve()
        sub = Path("f%d" % count[0])
        count[0] += 1
        if copy and src.is_file():
            _place(src, Path(dest_dir) / sub / src.name)
            for c in mesh_companions(src):
                csrc = (src.parent / c).resolve()
                cdest = (Path(dest_dir) / sub / c).resolve()
                if csrc.is_file() and str(cdest).startswith(str((Path(dest_dir) / sub).resolve()) + os.sep):
                    _place(csrc, cdest)
        return str(sub / src.name)

    def walk(node):
        if isinstance(node, dict):
            return {k: place(v) if k in FILE_KEYS and isinstance(v, str) else walk(v)
                    for k, v in node.items()}
        if isinstance(node, list):
            return [walk(v) for v in node]
        return node

    return walk(data)


def content_key(scene_bytes, data, base_dir, changes):
    """The hash of a scene's bytes, its referenced files' bytes (by their
    key path, not their location) and the changes applied to it."""
    h = hashlib.sha256()
    h.update(b"scene\0")
    h.update(scene_bytes)
    for where, path in referenced_files(data, base_dir):
        h.update(b"\0file\0" + where.encode() + b"\0")
        try:
            h.update(path.read_bytes())
        except OSError:
            # A missing file makes the renderers fail with a clear message;
            # hash the name so the key is still defined.
            h.update(b"missing:" + str(path).encode())
    h.update(b"\0changes\0" + json.dumps(changes, sort_keys=True).encode())
    return h.hexdigest()


def scaled_size(width, height, scale, min_size=1):
    """The image size after scaling both sides by `scale`, at least
    min_size pixels a side (and never more than asked for)."""
    if scale is None or scale == 1:
        return width, height
    w = max(min(width, min_size), int(round(width * scale)))
    h = max(min(height, min_size), int(round(height * scale)))
    return w, h


def write_atomic(path, text):
    """Writes text to path through a temporary file and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(".%s.tmp%d" % (path.name, os.getpid()))
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def prepare_data(name, data, base_dir, cache_dir, scene_bytes=None,
                 scale=None, source=None, min_size=8):
    """Writes the derived copy of the scene `data` (whose files are relative
    to base_dir) into cache_dir/scenes and returns its PreparedScene.
    `scale` multiplies the image size (None: unchanged)."""
    cam = data.get("camera", {})
    w0, h0 = int(cam.get("width", 1)), int(cam.get("height", 1))
    w, h = scaled_size(w0, h0, scale, min_size)
    changes = {"width": w, "height": h}
    if scene_bytes is None:
        scene_bytes = json.dumps(data, sort_keys=True).encode()
    key = content_key(scene_bytes, data, base_dir, changes)
    # The derived scene and its files' copies in a directory of their own,
    # made whole under a temporary name and renamed into place.
    where = Path(cache_dir) / "scenes" / ("%s-%s" % (name, key[:16]))
    path = where / ("%s.json" % name)
    tmp = where.with_name(".%s.tmp%d" % (where.name, os.getpid()))
    derived = localise(data, base_dir, tmp, copy=not path.exists())
    derived.setdefault("camera", {})
    derived["camera"] = dict(derived["camera"], width=w, height=h)
    if not path.exists():
        write_atomic(tmp / path.name, json.dumps(derived, indent=1) + "\n")
        try:
            os.rename(tmp, where)
        except OSError:  # made meanwhile by another process
            shutil.rmtree(tmp, ignore_errors=True)
    render = data.get("render", {}) if isinstance(data.get("render"), dict) else {}
    medium = data.get("medium")
    return PreparedScene(
        name=name, source=str(source or name), path=path, key=key,
        width=w, height=h, has_medium="medium" in data,
        exposure=float(render.get("exposure", 0.0)), data=derived,
        medium_type=(medium.get("type", "homogeneous") if isinstance(medium, dict)
                     else None))


def prepare_file(source, cache_dir, scale=None):
    """Reads a scene file and prepares it (see prepare_data). Raises
    ValueError with the file name if it is not JSON."""
    source = Path(source)
    raw = source.read_bytes()
    try:
        data = json.loads(raw)
    except ValueError as e:
        raise ValueError("%s: not a JSON scene: %s" % (source, e)) from e
    if not isinstance(data, dict):
        raise ValueError("%s: not a JSON object" % source)
    return prepare_data(source.stem, data, source.parent.resolve(), cache_dir,
                        scene_bytes=raw, scale=scale, source=source)


# The validation set is every scene of scenes/ (find_scenes). What a mode
# changes for one of them, by the scene file's stem: "scale" replaces the
# mode's image scale (validate.MODES) unless --scale is given. The
# non-uniform media of issue 12 cost more per pixel than the rest: the
# reference's optical depths by quadrature (the atmosphere), POV-Ray's
# density media, whose every sample's shadow ray is sampled as finely as
# the ray (docs/validation.md, "The renderers and their sweeps"). So the
# quick mode renders them at 40x30, where each renderer takes seconds
# (measured under load: the references at 512 spp 10 s, 4.8 s and 0.5 s,
# POV-Ray's quick sweep 1.5 s to 5 s), and the full mode at 64x48 (the
# sky's reference at 4096 spp alone would take over an hour at 320x240).
SCENE_MODES = {name: {"quick": {"scale": 0.125}, "full": {"scale": 0.2}}
               for name in ("sky_sunset", "earth_from_space", "valley_fog")}


def mode_scale(path, mode, scale):
    """The image scale of the scene file `path` in `mode`: the scene's own
    (SCENE_MODES) where it has one, else `scale` (the mode's)."""
    return SCENE_MODES.get(Path(path).stem, {}).get(mode, {}).get("scale", scale)


def find_scenes(args, default_dir):
    """The scene files named on the command line: files as given,
    directories as their *.json files (sorted); the default directory when
    nothing is named."""
    items = args or [default_dir]
    out = []
    for item in items:
        p = Path(item)
        if p.is_dir():
            out.extend(sorted(p.glob("*.json")))
        else:
            out.append(p)
    return out


# ---------------------------------------------------------------------------
# Where the camera sees the lights.

def _norm(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def camera_frame(camera):
    """The unit vectors forward, right and up of a scene's camera
    (sh_camera.c: right = forward x up, up = right x forward)."""
    fwd = _norm([b - a for a, b in zip(camera["position"], camera["look_at"])])
    right = _norm(_cross(fwd, camera.get("up", [0, 1, 0])))
    return fwd, right, _cross(right, fwd)


def pixel_direction(camera, x, y, width, height):
    """The unit direction of the camera ray through the continuous pixel
    coordinates (x, y) (x right, y down) of an image width x height."""
    fwd, right, up = camera_frame(camera)
    ty = math.tan(math.radians(camera["fov_y_deg"]) / 2)
    sx, sy = (2.0 * x / width - 1.0) * ty * width / height, (1.0 - 2.0 * y / height) * ty
    return _norm([f + r * sx + u * sy for f, r, u in zip(fwd, right, up)])


def project(camera, point):
    """The continuous pixel coordinates (x right, y down) where the camera
    sees `point` (sh_camera.c's pinhole), or None if it is behind."""
    pos = camera["position"]
    fwd, right, up = camera_frame(camera)
    d = [b - a for a, b in zip(pos, point)]
    z = _dot(d, fwd)
    if z <= 0:
        return None
    ty = math.tan(math.radians(camera["fov_y_deg"]) / 2)
    tx = ty * camera["width"] / camera["height"]
    sx, sy = _dot(d, right) / z / tx, _dot(d, up) / z / ty
    return ((sx + 1) / 2 * camera["width"], (1 - sy) / 2 * camera["height"])


def light_mask(scene, radius=None):
    """The pixel rectangles (x, y, w, h) around every point and spot light
    the camera sees: the square of pixels whose centres lie within `radius`
    pixels of the light's image along both axes (default: 5% of the image
    height, at least 1.5 pixels: a fixed solid angle, so the mask means the
    same at every image size). Next to a light in view the in-scattered
    radiance grows as 1/distance without bound, so a handful of pixels
    there can decide a relative RMS error alone."""
    cam = scene["camera"]
    if radius is None:
        radius = max(1.5, 0.05 * cam["height"])
    rects = []
    for light in scene.get("lights", []):
        if "position" not in light:
            continue
        p = project(cam, light["position"])
        if p is None:
            continue
        x0 = max(0, int(math.floor(p[0] - 0.5 - radius)) + 1)
        y0 = max(0, int(math.floor(p[1] - 0.5 - radius)) + 1)
        x1 = min(cam["width"] - 1, int(math.ceil(p[0] - 0.5 + radius)) - 1)
        y1 = min(cam["height"] - 1, int(math.ceil(p[1] - 0.5 + radius)) - 1)
        if x1 >= x0 and y1 >= y0:
            rects.append((x0, y0, x1 - x0 + 1, y1 - y0 + 1))
    return rects
