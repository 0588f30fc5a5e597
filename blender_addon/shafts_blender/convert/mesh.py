"""Evaluated Blender geometry as triangle arrays for the scene's mesh shapes.

Every object the depsgraph evaluates to geometry (meshes with their
modifiers, curves, surfaces, text, metaballs) gives one mesh per material
it uses: positions in object space in the scene's frame (float32, (n, 3))
and the triangles of `Mesh.loop_triangles` (int32, (m, 3), counter-clockwise
seen from outside as in Blender), read with `foreach_get` (no per-vertex
Python). They are the in-memory meshes of the format's project key
`{"type": "mesh", "data": NAME}` (sh_scene_parse_ex, CONTRACTS.md) and the
files the file export writes.

Exact: the triangles Cycles renders with flat shading. Approximated with a
warning: smooth shading (the scene's mesh triangles are flat-shaded).
"""
import numpy as np

from . import coords

GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "FONT", "META"}


class MeshPart:
    """The triangles of one object that use one material slot."""

    def __init__(self, positions, indices, slot):
        self.positions = positions  # float32 (n, 3), object space, scene frame
        self.indices = indices      # int32 (m, 3)
        self.slot = slot            # the material slot index


def _compact(positions, tris):
    used, inverse = np.unique(tris.reshape(-1), return_inverse=True)
    return (np.ascontiguousarray(positions[used]),
            inverse.reshape(-1, 3).astype(np.int32))


def mesh_parts(obj, warnings):
    """The evaluated object's triangles split by material slot (a list of
    MeshPart, empty if it has no triangles)."""
    try:
        me = obj.to_mesh()
    except RuntimeError:
        me = None
    if me is None:
        return []
    try:
        me.calc_loop_triangles()
        n, m = len(me.vertices), len(me.loop_triangles)
        if m == 0:
            return []
        co = np.empty(3 * n, dtype=np.float32)
        me.vertices.foreach_get("co", co)
        tris = np.empty(3 * m, dtype=np.int32)
        me.loop_triangles.foreach_get("vertices", tris)
        mats = np.empty(m, dtype=np.int32)
        me.loop_triangles.foreach_get("material_index", mats)
        if len(me.polygons):
            smooth = np.empty(len(me.polygons), dtype=bool)
            me.polygons.foreach_get("use_smooth", smooth)
            if smooth.any():
                warnings.add("The object '%s' is shaded smooth in Blender; the scene's "
                             "mesh triangles are flat-shaded." % obj.name)
    finally:
        obj.to_mesh_clear()
    positions = coords.points(co.reshape(-1, 3))
    tris = tris.reshape(-1, 3)
    nslots = max(1, len(obj.material_slots))
    mats = np.clip(mats, 0, nslots - 1)
    slots = np.unique(mats)
    if len(slots) == 1:
        return [MeshPart(positions, np.ascontiguousarray(tris), int(slots[0]))]
    parts = []
    for s in slots:
        p, t = _compact(positions, tris[mats == s])
        parts.append(MeshPart(p, t, int(s)))
    return parts


def is_box(positions, indices, matrix):
    """Whether the triangles, transformed by the 4x4 `matrix` (scene frame),
    fill their axis-aligned bounding box: (exact, lo, hi), with lo and hi
    the box's corners. Exact when the enclosed volume equals the box's
    within 1e-4 (a closed mesh that is an axis-aligned box)."""
    m = np.asarray(matrix, dtype=np.float64)
    p = positions.astype(np.float64) @ m[:3, :3].T + m[:3, 3]
    lo, hi = p.min(axis=0), p.max(axis=0)
    box = float(np.prod(hi - lo))
    a, b, c = p[indices[:, 0]], p[indices[:, 1]], p[indices[:, 2]]
    volume = abs(float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6.0)
    exact = box > 0 and abs(volume - box) <= 1e-4 * box
    return exact, [float(x) for x in lo], [float(x) for x in hi]
