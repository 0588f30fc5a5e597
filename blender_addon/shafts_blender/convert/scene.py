"""Blender -> scene: the evaluated depsgraph as a scene of the format.

    export_scene(depsgraph, *, view=None, size=None) -> Export
    export_patch(depsgraph, previous, *, view=None, size=None) -> dict | None

The depsgraph's object instances (instancing, modifiers, particles) are read
after evaluation; lights go to light.py, geometry to mesh.py and
material.py, volumes and the World to medium.py, the camera (or a 3D
viewport's view: `view` = (view_matrix, projection_matrix)) to camera.py.
Every approximation is one sentence in Export.warnings; nothing here raises
for a scene it cannot represent exactly.

Meshes are in memory (Export.meshes: name -> (positions (n, 3) float32,
indices (m, 3) int32)) and the scene names them with the project key
{"type": "mesh", "data": NAME} (sh_scene_parse_ex, CONTRACTS.md).
files.py writes the same scene with the meshes as files.
"""
import json

import numpy as np

from . import camera as cam
from . import cards as cd
from . import coords
from . import light as lt
from . import material as mt
from . import medium as md
from . import mesh as ms
from .warnings import Warnings

NO_MATERIAL = "(no material)"


class Export:
    """One export: `.text` (the scene's JSON), `.scene` (the same as a
    dict), `.meshes` (name -> (positions, indices)), `.warnings` (list of
    sentences), `.shape_objects` (shape index -> object name)."""

    def __init__(self, scene, meshes, warnings, shape_objects, structure):
        self.scene = scene
        self.meshes = meshes
        self.warnings = list(warnings)
        self.shape_objects = shape_objects
        self.structure = structure
        self.text = json.dumps(scene)


def _instances(depsgraph):
    """(evaluated object, world matrix copy) for every instance the
    depsgraph shows."""
    for inst in depsgraph.object_instances:
        if not inst.is_instance and not getattr(inst, "show_self", True):
            continue
        yield inst.object, inst.matrix_world.copy()


def _material_slots(obj):
    return [slot.material for slot in obj.material_slots] or [None]


def _material_name(mat):
    return NO_MATERIAL if mat is None else mat.name_full


class _Collector:
    """Walks the depsgraph once; with_meshes=False skips shape triangles
    (for patches), reading only the medium's."""

    def __init__(self, depsgraph, warnings, with_meshes=True, known=None, boxes=None):
        self.warnings = warnings
        self.known = known or {}  # object name -> its shape keys (patches)
        self.unknown = False      # a patch met an object the export did not have
        self.lights, self.light_keys = [], []
        self.shapes, self.shape_objects, self.shape_keys = [], [], []
        self.meshes, self.materials = {}, {}
        self.points = []  # scene points for the World volume's box
        self.media = []   # (name, coefficients, lo, hi)
        self.cards = []   # (object name, card): light filters (cards.py)
        self.object_keys = {}  # object name -> its shape keys (empty: no triangles)
        self.boxes = dict(boxes or {})  # mesh name -> object-space (lo, hi)
        self._parts_cache = {}
        self._with_meshes = with_meshes
        self._scene = depsgraph.scene
        # The tessellated ground scene_export's Blender writer builds under
        # an atmosphere (marked shafts_atmosphere_ground): the atmosphere's
        # own ground sphere replaces it, so it is read only without one.
        grounds = []
        for obj, m in _instances(depsgraph):
            if obj.get("shafts_atmosphere_ground"):
                grounds.append((obj, m))
                continue
            self._read(obj, m)
        if not any(fixed is not None and fixed.get("type") == "atmosphere"
                   for *_, fixed in self.media):
            for obj, m in grounds:
                self._read(obj, m)

    def _read(self, obj, m):
        try:
            self._instance(obj, m)
        except Exception as e:  # a Blender datum this code did not foresee
            self.warnings.add("The object '%s' could not be read (%s: %s); it is left out."
                              % (obj.name, type(e).__name__, e))

    def _instance(self, obj, m):
        warnings, with_meshes, parts_cache = self.warnings, self._with_meshes, self._parts_cache
        if obj.type == "LIGHT":
            d = lt.export_light(obj, m, warnings)
            if d is not None:
                self.lights.append(d)
                self.light_keys.append((obj.name, d["type"]))
                self.points.append(d.get("position", [0.0, 0.0, 0.0]))
            return
        if obj.type not in ms.GEOMETRY_TYPES:
            return
        slots = _material_slots(obj)
        volume = next((mat for mat in slots if mat is not None and mt.has_volume(mat)), None)
        surface = volume is None or mt.has_surface(volume)
        t = coords.transform(m)
        if volume is None and not getattr(obj, "visible_camera", True):
            card = cd.read_card(obj, m)
            if card is not None:
                self.cards.append((obj.name, card))
            else:
                warnings.add("The object '%s' is hidden from camera rays (a shadow or "
                             "light filter); the scene has no such object, so it is left "
                             "out." % obj.name)
            return
        if abs(np.linalg.det(t[:3, :3])) < 1e-12:
            warnings.add("The object '%s' is scaled to zero; it is left out." % obj.name)
            return
        need_mesh = with_meshes or volume is not None
        parts = None
        if need_mesh:
            parts = parts_cache.get(obj.name)
            if parts is None:
                parts = parts_cache[obj.name] = ms.mesh_parts(obj, warnings)
        if volume is not None and parts:
            self._medium_object(obj, volume, parts, t)
        if not surface:
            return
        if parts is not None:
            entries = [(slots[min(p.slot, len(slots) - 1)], p) for p in parts]
            keys = [(obj.name, obj.name if len(entries) == 1 else
                     "%s [%s]" % (obj.name, _material_name(mat)), _material_name(mat))
                    for mat, _ in entries]
            self.object_keys[obj.name] = keys
        else:  # a patch: the shapes the previous export found
            keys = self.known.get(obj.name)
            if keys is None:
                self.unknown = True
                return
            entries = [(None, None)] * len(keys)
        for (oname, data, mname), (mat, part) in zip(keys, entries):
            if part is not None:
                if mname not in self.materials:
                    self.materials[mname] = mt.export_material(mat, warnings)
                self.meshes[data] = (part.positions, part.indices)
                self.boxes[data] = (part.positions.min(axis=0), part.positions.max(axis=0))
            # The World volume's box holds every shape's transformed bounding
            # box, the same in a patch (which reads no triangles).
            box = self.boxes.get(data)
            if box is not None:
                corners = np.array([[box[i >> k & 1][k] for k in range(3)] for i in range(8)])
                self.points.extend(corners @ t[:3, :3].T + t[:3, 3])
            self.shapes.append({"type": "mesh", "data": data, "material": mname,
                                "transform": coords.matrix_key(t)})
            self.shape_objects.append(obj.name)
            self.shape_keys.append((oname, data, mname))

    def _medium_object(self, obj, mat, parts, t):
        what = "The volume of '%s' (material '%s')" % (obj.name, mat.name)
        pos = np.concatenate([p.positions for p in parts])
        offs = np.cumsum([0] + [len(p.positions) for p in parts[:-1]])
        idx = np.concatenate([p.indices + o for p, o in zip(parts, offs)])
        exact, lo, hi = ms.is_box(pos, idx, t)
        # The add-on's properties (height fog, atmosphere) when set, else
        # the node graph's homogeneous medium.
        fixed = md.from_properties(mat, md.object_frame(getattr(obj, "original", obj),
                                                        self._scene),
                                   lo, hi, what, self.warnings)
        if fixed is not None and fixed["type"] == "atmosphere":
            self.media.append((obj.name, None, None, None, fixed))
            return
        coeffs = None
        if fixed is None:
            coeffs = md.coefficients(mt.surface_output(mat), what, self.warnings,
                                     md.written_phase(mat))
            if coeffs is None:
                return
        if not exact:
            self.warnings.add("%s is not an axis-aligned box; the medium fills its "
                              "bounding box." % what)
        self.media.append((obj.name, coeffs, lo, hi, fixed))


def _build(depsgraph, view, size, with_meshes, known=None, boxes=None):
    warnings = Warnings()
    scene = depsgraph.scene
    c = _Collector(depsgraph, warnings, with_meshes, known, boxes)
    for name in cd.attach(c.lights, c.cards, warnings):
        warnings.add("The object '%s' filters light for shadow rays only but fits no "
                     "light as a light map; the scene has no such object, so it is left "
                     "out." % name)
    camera = cam.export_camera(depsgraph, scene, warnings, view=view, size=size)
    out = {"format": "shafts-scene", "version": 1, "camera": camera,
           "background": md.export_background(scene.world, warnings),
           "ambient": [0.0, 0.0, 0.0]}
    medium_key = None
    world_coeffs = None
    if scene.world is not None:
        world_coeffs = md.coefficients(md.world_output(scene.world),
                                       "The world '%s' volume" % scene.world.name, warnings)
    if c.media:
        name, coeffs, lo, hi, fixed = c.media[0]
        for other in c.media[1:]:
            warnings.add("The volume of '%s' is left out: the scene has one medium, that "
                         "of '%s'." % (other[0], name))
        if world_coeffs is not None:
            warnings.add("The world's volume is left out: the scene has one medium, that "
                         "of '%s'." % name)
        out["medium"] = fixed if fixed is not None else md.medium(coeffs, lo, hi)
        medium_key = ("object", name)
    elif world_coeffs is not None:
        lo, hi = md.world_box(c.points + [camera["position"]])
        warnings.add("The world '%s' has a volume, which has no end in Cycles; the scene's "
                     "medium fills the box from (%.4g, %.4g, %.4g) to (%.4g, %.4g, %.4g) "
                     "(scene frame) around the camera, the lights and the shapes, with "
                     "vacuum beyond." % (scene.world.name, *lo, *hi))
        if any(l["type"] == "directional" for l in c.lights):
            warnings.add("A sun inside the world's volume lights nothing in Cycles (its "
                         "shadow ray never ends); the scene attenuates it from the "
                         "medium's box instead.")
        out["medium"] = md.medium(world_coeffs, lo, hi)
        medium_key = ("world", scene.world.name)
    out["lights"] = c.lights
    out["materials"] = c.materials
    out["shapes"] = c.shapes
    if not c.lights:
        warnings.add("The scene has no light the format can represent; it renders black "
                     "but for emission and the background.")
    structure = {"lights": c.light_keys, "shapes": c.shape_keys, "medium": medium_key,
                 "objects": c.object_keys, "boxes": c.boxes,
                 "size": (camera["width"], camera["height"])}
    return out, c, warnings, structure


def export_scene(depsgraph, *, view=None, size=None):
    """The scene the depsgraph shows, with its meshes in memory."""
    out, c, warnings, structure = _build(depsgraph, view, size, True)
    return Export(out, c.meshes, warnings, c.shape_objects, structure)


def _structure_edits(depsgraph, previous):
    """Whether an update since the last evaluation changed what a patch
    cannot carry: geometry of a shape, or a surface material."""
    shape_objects = set(previous.shape_objects)
    import bpy
    for u in depsgraph.updates:
        ident = u.id
        if isinstance(ident, bpy.types.Object):
            if u.is_updated_geometry and ident.name in shape_objects:
                return True
        elif isinstance(ident, bpy.types.Mesh):
            if u.is_updated_geometry:
                return True
        elif isinstance(ident, bpy.types.Material):
            if u.is_updated_shading and mt.has_surface(ident):
                return True
    return False


def export_patch(depsgraph, previous, *, view=None, size=None):
    """What changed since `previous` (an Export) as a patch for
    Scene.update / sh_scene_update: "camera", "lights", "medium",
    "background", "ambient" and "transforms" (one entry per shape, null when
    unchanged). None when the structure changed (lights added, removed or of
    another type; shapes, materials or geometry changed; the medium appeared
    or went): rebuild with export_scene. `previous.scene` is updated to the
    patched values, so the next patch is relative to this one."""
    if _structure_edits(depsgraph, previous):
        return None
    out, c, warnings, structure = _build(depsgraph, view, size, False,
                                         previous.structure["objects"],
                                         previous.structure["boxes"])
    old = previous.structure
    if (c.unknown or structure["lights"] != old["lights"]
            or structure["shapes"] != old["shapes"]
            or (structure["medium"] is None) != (old["medium"] is None)):
        return None
    patch = {"camera": out["camera"], "lights": out["lights"],
             "background": out["background"], "ambient": out["ambient"]}
    if "medium" in out:
        patch["medium"] = out["medium"]
    transforms = []
    for new, prev in zip(out["shapes"], previous.scene["shapes"]):
        same = np.allclose(new["transform"]["matrix"], prev["transform"]["matrix"],
                           rtol=0.0, atol=0.0)
        transforms.append(None if same else new["transform"])
        prev["transform"] = new["transform"]
    patch["transforms"] = transforms
    for key in ("camera", "lights", "background", "ambient", "medium"):
        if key in out:
            previous.scene[key] = out[key]
    structure["objects"] = previous.structure["objects"]
    structure["boxes"] = previous.structure["boxes"]
    previous.structure = structure
    previous.warnings = list(warnings)
    previous.text = json.dumps(previous.scene)
    return patch
