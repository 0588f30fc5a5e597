"""Light-filter cards as the scene's light maps.

scene_export's Blender writer (docs/scene_export.md; the import builds the
same objects) turns a light map into a card: a parallelogram hidden from
camera rays, whose material lets shadow rays through a Transparent BSDF
coloured by an Image Texture; a window also gets a black wall around its
card. The export reads such a card back (whoever built it):

- a card square to a spot's axis, centred on it in front of the light: the
  spot's `light_map` with `up` along the image's top. The format fixes the
  map's extent to the cone ([-tan outer, tan outer]^2 at unit distance);
  a card of another size is approximated with a warning. A card that
  corrects Cycles' cos term for another exponent (cos^(e-1)/k, with the
  power times k) comes back as such a map: the same light.
- a card not parallel to the sun: the directional light's window, origin
  at the image's top-left corner, u along its top edge, v down its left
  edge. The format projects a window along the light and blocks the light
  outside it, so the card may lie anywhere along the light and the wall is
  the format's own rule: it is left out.

Images the card holds in Blender only (packed, as the import leaves them,
or generated) are written as PFM (32-bit float, linear, rows bottom to top
as Blender stores them) into a directory that lives as long as Blender;
files.write_files copies them beside the scene.
"""
import atexit
import math
import os
import shutil
import tempfile

import numpy as np

from . import coords
from . import nodes as nd

_cache_dir = None


def _cache():
    global _cache_dir
    if _cache_dir is None:
        _cache_dir = tempfile.mkdtemp(prefix="shafts_maps_")
        atexit.register(shutil.rmtree, _cache_dir, True)
    return _cache_dir


def is_cached(path):
    return _cache_dir is not None and os.path.dirname(path) == _cache_dir


def image_file(image):
    """A file holding the image's linear values: its own file when it is an
    unpacked file on disk, else a PFM in the cache (None if it has no
    pixels)."""
    import bpy
    if image.source == "FILE" and image.packed_file is None and image.filepath:
        path = bpy.path.abspath(image.filepath, library=image.library)
        if os.path.isfile(path):
            return path
    w, h, c = image.size[0], image.size[1], image.channels
    if w * h * c == 0:
        return None
    px = np.empty(w * h * c, dtype=np.float32)
    image.pixels.foreach_get(px)
    px = px.reshape(h, w, c)
    rgb = px[:, :, :3] if c >= 3 else np.repeat(px[:, :, :1], 3, axis=2)
    path = os.path.join(_cache(), "map_%d.pfm" % (abs(hash(image.name_full)) % 10 ** 9))
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        f.write(np.ascontiguousarray(rgb, dtype="<f4").tobytes())
    return path


def _filter_image(mat):
    """(is_card, image): whether the material is a shadow-ray filter
    (Transparent BSDFs, maybe mixed by Is Shadow Ray) and the Image
    Texture on its Transparent colour, if any."""
    if mat is None or not mat.use_nodes or mat.node_tree is None:
        return False, None
    kinds = {n.bl_idname for n in mat.node_tree.nodes}
    if "ShaderNodeBsdfTransparent" not in kinds:
        return False, None
    for n in mat.node_tree.nodes:
        if n.bl_idname == "ShaderNodeBsdfTransparent":
            src, _ = nd.source(n.inputs["Color"])
            if src is not None and src.bl_idname == "ShaderNodeTexImage" and src.image:
                return True, src.image
    return True, None


def read_card(obj, matrix):
    """The card an evaluated object hidden from camera rays is, or None:
    {"image": Image or None (a wall), "corners": {(u, v): scene point}}."""
    slots = [s.material for s in obj.material_slots]
    is_card, image = _filter_image(slots[0] if slots else None)
    if not is_card:
        return None
    me = obj.to_mesh()
    try:
        if image is None:
            return {"image": None, "corners": {}}
        if len(me.vertices) != 4 or not me.uv_layers:
            return None
        uv = np.empty(2 * len(me.loops), dtype=np.float32)
        me.uv_layers.active.data.foreach_get("uv", uv)
        vi = np.empty(len(me.loops), dtype=np.int32)
        me.loops.foreach_get("vertex_index", vi)
        co = np.empty(3 * len(me.vertices), dtype=np.float32)
        me.vertices.foreach_get("co", co)
    finally:
        obj.to_mesh_clear()
    m = coords.transform(matrix)
    p = coords.points(co.reshape(-1, 3)).astype(np.float64) @ m[:3, :3].T + m[:3, 3]
    corners = {}
    for (u, v), k in zip(np.round(uv.reshape(-1, 2)).astype(int), vi):
        corners[(int(u), int(v))] = p[k]
    if set(corners) != {(0, 0), (1, 0), (0, 1), (1, 1)}:
        return None
    return {"image": image, "corners": corners}


def _unit(v):
    n = np.linalg.norm(v)
    return v / n if n > 0 else v


def attach(lights, cards, warnings):
    """Gives the lights the maps of the cards that filter them; returns the
    names of the cards that fit no light. `lights` are the format's light
    dicts, `cards` (name, card) pairs."""
    unused = []
    mapped_sun = False
    for name, card in cards:
        if card["image"] is None:
            continue
        c = card["corners"]
        bl, br, tl = c[(0, 0)], c[(1, 0)], c[(0, 1)]
        right, up = br - bl, tl - bl
        normal = _unit(np.cross(right, up))
        centre = (br + tl) / 2
        target = None
        for light in lights:
            if "light_map" in light:
                continue
            if light["type"] == "spot" and light["outer_angle_deg"] < 89.999:
                a, o = np.asarray(light["direction"]), np.asarray(light["position"])
                d = float(np.dot(centre - o, a))
                off = np.linalg.norm(centre - o - d * a)
                if d > 0 and off <= 1e-4 * max(d, np.linalg.norm(right)) \
                        and abs(np.dot(normal, a)) > 1 - 1e-6 \
                        and np.dot(np.cross(a, _unit(up)), _unit(right)) > 0.999:
                    target = light
                    half = np.linalg.norm(right) / 2
                    want = d * math.tan(math.radians(light["outer_angle_deg"]))
                    if abs(half - want) > 1e-3 * want:
                        warnings.add("The card '%s' in front of a spot is not the size of "
                                     "its cone; the scene's light map spans the cone."
                                     % name)
                    break
            elif light["type"] == "directional" and \
                    abs(np.dot(normal, light["direction"])) > 1e-6:
                target = light
                break
        if target is None:
            unused.append(name)
            continue
        path = image_file(card["image"])
        if path is None:
            unused.append(name)
            continue
        if target["type"] == "spot":
            target["light_map"] = {"image": path, "up": [float(x) for x in _unit(up)]}
        else:
            mapped_sun = True
            target["light_map"] = {"image": path, "origin": [float(x) for x in tl],
                                   "u": [float(x) for x in c[(1, 1)] - tl],
                                   "v": [float(x) for x in bl - tl]}
    walls = [name for name, card in cards if card["image"] is None]
    if not mapped_sun:
        unused.extend(walls)
    return unused
