"""Blender volumes as the scene's medium.

The scene's medium is one homogeneous box with sigma_s, sigma_a and a phase
function (docs/scene-format.md, medium). It comes from:

- an object whose material drives the Volume output: the box is the
  object's evaluated bounding box in the scene's frame (exact when the mesh
  is an axis-aligned box: its enclosed volume equals the box's within 1e-4;
  any other shape: approximated by its box, with a warning);
- else the World's Volume output: a box around the camera, the lights and
  every shape, enlarged by WORLD_MARGIN of its diagonal on each side
  (approximated: Cycles' world volume has no end, so rays that leave the box
  see vacuum, and a sun inside a world volume lights nothing in Cycles).

Coefficients, per scene unit as Cycles 3.4 computes them
(renderer-semantics.md; intern/cycles/kernel/svm/closure.h):

| node | sigma_s | sigma_a | phase |
|---|---|---|---|
| Volume Scatter | Color Density | 0 | HG, g = Anisotropy |
| Volume Absorption | 0 | (1 - Color) Density | |
| Principled Volume | Color Density | max(1 - Color, 0) max(1 - sqrt(Absorption Color), 0) Density | HG, g = Anisotropy |

Add Shader sums, a Mix Shader with a constant factor weights. Cycles merges
scattering closures of equal g and sums the phases of n distinct ones
without their weights: the medium in-scatters n sigma_s with the
equal-weight mean of the lobes, approximated by one lobe of their mean g,
and its absorption is sigma_a + sigma_s - n sigma_s so that the extinction
stays Cycles' (scene_export's mixtures come back exactly but for the phase); emission and linked (textured) densities are
approximated with warnings. g is clamped to +-0.999 as Cycles clamps it, and
g = 0 is the isotropic phase.

A homogeneous medium imported from a scene file carries the scene's own
phase on its material (raw property shafts_phase, blender_build.phase_record:
Cycles has no Nishita, Rayleigh or Cornette-Shanks phase, our engines do);
while the graph still holds the lobes the writer built for it, that phase
is the medium's (written_phase), else the graph's lobes as above.

A material whose add-on properties (material.shafts_medium, properties.py)
name height fog or an atmosphere is read from them instead, exactly
(from_properties): the node graph, which Cycles renders, is then not read.
Their numbers are in the scene's units and frame; when the object's
collection (or the scene's) holds scene_export's frame (shafts_scale,
shafts_origin, shafts_axes: a scene scaled and moved so that Cycles' single
precision holds it, importer.py), they are mapped through it into Blender's
frame, where the rest of the Blender scene is: points p -> (p - origin)
scale along the named axes, lengths times scale, coefficients divided by
it. scene_export's Blender writer stores the scene's own medium there in
double precision (blender_build.set_medium_properties), and the raw values
are read, so a round trip keeps every digit.
"""
import numpy as np

from . import nodes as nd

WORLD_MARGIN = 0.1
G_MAX = 0.999


class _Volume:
    def __init__(self, what, warnings):
        self.what, self.warnings = what, warnings
        self.sigma_s = np.zeros(3)
        self.sigma_a = np.zeros(3)
        self.lobes = []  # (weight, g)

    def scatter(self, rgb, density, g, w):
        s = np.asarray(rgb) * density * w
        self.sigma_s += s
        self.lobes.append((float(s.mean()), g))


def _walk(node, v, w, depth=0):
    what, warn = v.what, v.warnings
    if node is None or w == 0.0 or depth > 64:
        return
    kind = node.bl_idname
    g = lambda names, default=0.0: nd.scalar(node, names, what, warn, default)
    if kind == "ShaderNodeAddShader":
        for k in (0, 1):
            _walk(nd.source(node.inputs[k])[0], v, w, depth + 1)
    elif kind == "ShaderNodeMixShader":
        fac = node.inputs[0]
        if fac.is_linked:
            warn.add("%s mixes volumes by a linked factor; the scene takes half of each."
                     % what)
            f = 0.5
        else:
            f = min(max(float(fac.default_value), 0.0), 1.0)
        _walk(nd.source(node.inputs[1])[0], v, w * (1 - f), depth + 1)
        _walk(nd.source(node.inputs[2])[0], v, w * f, depth + 1)
    elif kind == "ShaderNodeVolumeScatter":
        v.scatter(nd.colour(node, "Color", what, warn), g("Density", 1.0),
                  g("Anisotropy"), w)
    elif kind == "ShaderNodeVolumeAbsorption":
        c = np.asarray(nd.colour(node, "Color", what, warn))
        v.sigma_a += np.maximum(1.0 - c, 0.0) * g("Density", 1.0) * w
    elif kind == "ShaderNodeVolumePrincipled":
        c = np.asarray(nd.colour(node, "Color", what, warn))
        density = g("Density", 1.0)
        ac = np.asarray(nd.colour(node, "Absorption Color", what, warn))
        v.scatter(c, density, g("Anisotropy"), w)
        v.sigma_a += (np.maximum(1.0 - c, 0.0) * np.maximum(1.0 - np.sqrt(ac), 0.0)
                      * density * w)
        if g("Emission Strength") > 0 or g("Blackbody Intensity") > 0:
            warn.add("%s emits light from its volume; the scene's medium does not, so "
                     "the emission is left out." % what)
    else:
        warn.add("%s uses a '%s' node in its volume, which the scene has no counterpart "
                 "for; it is left out." % (what, node.name))


def written_phase(mat):
    """scene_export's record of a homogeneous medium's own phase on its
    material (raw property shafts_phase, blender_build.phase_record): (the
    format's phase object, the sorted g of the lobes the writer built), or
    None."""
    raw = mat.get("shafts_phase") if mat is not None else None
    if raw is None:
        return None
    try:
        t = PHASE_TYPES[int(raw.get("phase"))]
        phase = {"type": t}
        if t in ("henyey_greenstein", "cornette_shanks"):
            phase["g"] = float(raw.get("phase_g"))
        lobes = sorted({round(float(g), 6) for g in raw.get("lobes")})
    except (IndexError, TypeError, ValueError, AttributeError):
        return None
    return phase, lobes


def coefficients(output_node, what, warnings, written=None):
    """(sigma_s, sigma_a, phase) of the shader on an output node's Volume
    input, or None if it gives no medium. With `written` (written_phase of
    the material) and the graph's lobes still the ones the writer built,
    the phase is the scene's own, exactly: Cycles cannot hold a Nishita,
    Rayleigh or Cornette-Shanks phase, our engines can."""
    if output_node is None or "Volume" not in output_node.inputs:
        return None
    node, _ = nd.source(output_node.inputs["Volume"])
    if node is None:
        return None
    v = _Volume(what, warnings)
    _walk(node, v, 1.0)
    if not v.sigma_s.any() and not v.sigma_a.any():
        return None
    if (v.sigma_s < 0).any() or (v.sigma_a < 0).any():
        warnings.add("%s has a negative density or colour; the scene's coefficients "
                     "are clamped at 0." % what)
    sigma_s, sigma_a = np.maximum(v.sigma_s, 0.0), np.maximum(v.sigma_a, 0.0)
    gs = sorted({round(gv, 6) for wt, gv in v.lobes if wt > 0})
    gmean = sum(gs) / len(gs) if gs else 0.0
    n = len(gs)
    own = (written is not None and len(written[1]) == n
           and all(abs(a - b) <= 1e-5 for a, b in zip(written[1], gs)))
    if n > 1:
        # Cycles 3.4 merges closures of equal g and sums the phases of the
        # rest without their weights (docs/scene_export.md, facts verified by
        # renders): it in-scatters n sigma_s times the equal-weight mean of
        # the n lobes while its extinction stays sigma_s + sigma_a.
        sigma_a = sigma_a + sigma_s - n * sigma_s
        sigma_s = n * sigma_s
        if (sigma_a < -1e-12).any():
            warnings.add("%s scatters more than its extinction allows in the scene's "
                         "model (Cycles sums the phases of its %d lobes); its absorption "
                         "is clamped at 0." % (what, n))
        sigma_a = np.maximum(sigma_a, 0.0)
    if n > 1 and not own:
        warnings.add("%s has %d scattering lobes, whose phases Cycles sums; the scene's "
                     "medium scatters %d times their density with one Henyey-Greenstein "
                     "lobe of their mean g = %.4g." % (what, n, n, gmean))
    gmean = min(max(gmean, -G_MAX), G_MAX)
    phase = ({"type": "isotropic"} if gmean == 0.0
             else {"type": "henyey_greenstein", "g": float(gmean)})
    if own:
        phase = dict(written[0])
    return ([float(x) for x in sigma_s], [float(x) for x in sigma_a], phase)


def medium(coeffs, lo, hi):
    """The format's medium object from coefficients and box corners (kept
    non-degenerate)."""
    sigma_s, sigma_a, phase = coeffs
    lo, hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    pad = np.maximum(1e-6 * max(1.0, float(np.abs(hi - lo).max())) - (hi - lo) / 2, 0.0)
    lo, hi = lo - pad, hi + pad
    return {"sigma_s": sigma_s, "sigma_a": sigma_a, "phase": phase,
            "bounds": {"min": [float(x) for x in lo], "max": [float(x) for x in hi]}}


def world_box(points):
    """The box around the given scene points (an (n, 3) array), enlarged by
    WORLD_MARGIN of its diagonal on every side."""
    p = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    lo, hi = p.min(axis=0), p.max(axis=0)
    d = max(float(np.linalg.norm(hi - lo)), 1.0)
    return lo - WORLD_MARGIN * d, hi + WORLD_MARGIN * d


def world_output(world):
    tree = world.node_tree if world is not None and world.use_nodes else None
    if tree is None:
        return None
    out = tree.get_output_node("CYCLES") if hasattr(tree, "get_output_node") else None
    if out is None:
        out = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputWorld"
                    and n.is_active_output), None)
    return out


def _background(node, warnings, what, depth=0):
    """The radiance a world shader shows, and whether it lights the scene."""
    if node is None or depth > 16:
        return [0.0, 0.0, 0.0], False
    kind = node.bl_idname
    if kind == "ShaderNodeBackground":
        c = nd.colour(node, "Color", what, warnings)
        s = nd.scalar(node, "Strength", what, warnings, 1.0)
        return [x * s for x in c], True
    if kind == "ShaderNodeMixShader":
        src, sock = nd.source(node.inputs[0])
        if src is not None and nd.is_light_path_gate(src, sock):
            c, _ = _background(nd.source(node.inputs[2])[0], warnings, what, depth + 1)
            return c, False
        f = 0.5 if src is not None else min(max(float(node.inputs[0].default_value), 0.0), 1.0)
        a, la = _background(nd.source(node.inputs[1])[0], warnings, what, depth + 1)
        b, lb = _background(nd.source(node.inputs[2])[0], warnings, what, depth + 1)
        return [(1 - f) * x + f * y for x, y in zip(a, b)], la or lb
    if kind == "ShaderNodeAddShader":
        a, la = _background(nd.source(node.inputs[0])[0], warnings, what, depth + 1)
        b, lb = _background(nd.source(node.inputs[1])[0], warnings, what, depth + 1)
        return [x + y for x, y in zip(a, b)], la or lb
    warnings.add("%s uses a '%s' node, which the scene has no counterpart for; the "
                 "background is black." % (what, node.name))
    return [0.0, 0.0, 0.0], False


def export_background(world, warnings):
    """The format's background radiance from the World. Cycles' world also
    lights the scene, the format's background does not (exact only when the
    World is gated to traced rays, as scene_export's Blender writer builds
    it)."""
    if world is None:
        return [0.0, 0.0, 0.0]
    what = "The world '%s'" % world.name
    out = world_output(world)
    if out is None:
        if world.use_nodes:
            return [0.0, 0.0, 0.0]
        c, lights = [max(0.0, float(x)) for x in world.color[:3]], True
    else:
        c, lights = _background(nd.source(out.inputs["Surface"])[0], warnings, what)
        c = [max(0.0, x) for x in c]
    if lights and max(c) > 0:
        warnings.add("%s lights the scene in Cycles; the scene's background (%.3g, %.3g, "
                     "%.3g) is only seen by camera, mirror and refracted rays."
                     % (what, *c))
    return c


# The scene format's phase types by the properties' enum numbers
# (properties.PHASES, blender_build.MEDIUM_PHASES).
PHASE_TYPES = ("isotropic", "henyey_greenstein", "nishita_hazy", "nishita_murky",
               "rayleigh", "cornette_shanks")
KINDS = ("NODES", "HEIGHT_FOG", "ATMOSPHERE")


def kind(mat):
    """'NODES', 'HEIGHT_FOG' or 'ATMOSPHERE': what the material's add-on
    properties say ('NODES' without them or without the add-on)."""
    settings = getattr(mat, "shafts_medium", None)
    if settings is not None:
        return settings.kind
    raw = mat.get("shafts_medium") if mat is not None else None
    k = raw.get("kind", 0) if raw is not None else 0
    return KINDS[k] if isinstance(k, int) and 0 <= k < len(KINDS) else "NODES"


def _value(settings, key):
    """A property's stored value in double precision (the raw ID property
    the writer or the UI set), else its RNA default."""
    raw = settings.get(key) if hasattr(settings, "get") else None
    if raw is None:
        v = getattr(settings, key)
    else:
        v = raw
    if hasattr(v, "__len__") and not isinstance(v, str):
        return np.array([float(x) for x in v], dtype=np.float64)
    return float(v) if not isinstance(v, str) else v


def _phase(settings, type_key, g_key):
    t = getattr(settings, type_key)
    name = t.lower() if isinstance(t, str) else PHASE_TYPES[int(t)]
    phase = {"type": name}
    if name in ("henyey_greenstein", "cornette_shanks"):
        phase["g"] = _value(settings, g_key)
    return phase


class Frame:
    """scene_export's frame (importer.py): Blender point B = axes-mapped
    (p - origin) * scale of a scene point p, then the add-on's scene point
    coords.SCENE_FROM_BLENDER B."""

    def __init__(self, scale=1.0, origin=(0.0, 0.0, 0.0), axes="+x -z +y"):
        from . import coords
        self.scale = float(scale)
        self.origin = np.asarray(origin, dtype=np.float64)
        m = np.zeros((3, 3))
        for i, a in enumerate(str(axes).split()):
            m[i, "xyz".index(a[1])] = -1.0 if a[0] == "-" else 1.0
        self.rot = coords.SCENE_FROM_BLENDER @ m  # scene dir -> add-on scene dir

    def point(self, p):
        return self.rot @ ((np.asarray(p, dtype=np.float64) - self.origin) * self.scale)

    def dir(self, d):
        return self.rot @ np.asarray(d, dtype=np.float64)

    def identity(self):
        return self.scale == 1.0 and not self.origin.any() and (self.rot == np.eye(3)).all()


def object_frame(obj, scene=None):
    """The frame of the first of the object's collections (then the
    scene's master collection) that holds shafts_scale, else the identity."""
    owners = list(getattr(obj, "users_collection", ()) or ())
    if scene is not None:
        owners.append(scene.collection)
    for c in owners:
        if c is not None and c.get("shafts_scale") is not None:
            return Frame(c.get("shafts_scale"), list(c.get("shafts_origin", (0.0, 0.0, 0.0))),
                         c.get("shafts_axes", "+x -z +y"))
    return Frame()


def _rgb_list(v):
    return [float(x) for x in v]


def from_properties(mat, frame, lo, hi, what, warnings):
    """The format's medium from the material's add-on properties (height
    fog in the box lo-hi, scene frame of the add-on; an atmosphere), or None
    when they name no such medium (then the node graph is read)."""
    k = kind(mat)
    if k == "NODES":
        return None
    settings = getattr(mat, "shafts_medium", None)
    if settings is None:  # the add-on's classes not registered: raw values
        return None
    s = frame.scale
    if k == "HEIGHT_FOG":
        up = frame.dir([0.0, 1.0, 0.0])
        if not np.allclose(up, [0.0, 1.0, 0.0], atol=1e-12):
            warnings.add("%s is height fog in a frame whose Y is not Blender's Z (its "
                         "collection's shafts_axes); the scene's height fog is vertical, "
                         "so the node graph is read instead." % what)
            return None
        base = frame.point([0.0, _value(settings, "base_height"), 0.0])[1]
        out = medium((_rgb_list(_value(settings, "sigma_s") / s),
                      _rgb_list(_value(settings, "sigma_a") / s),
                      _phase(settings, "phase", "phase_g")), lo, hi)
        out.update({"type": "height_fog", "base_height": float(base),
                    "scale_height": _value(settings, "scale_height") * s})
        return out
    out = {"type": "atmosphere",
           "center": _rgb_list(frame.point(_value(settings, "center"))),
           "ground_radius": _value(settings, "ground_radius") * s,
           "top_radius": _value(settings, "top_radius") * s,
           "ground_albedo": _rgb_list(_value(settings, "ground_albedo")),
           "rayleigh": {"sigma_s": _rgb_list(_value(settings, "rayleigh_sigma_s") / s),
                        "scale_height": _value(settings, "rayleigh_scale_height") * s}}
    if settings.use_mie:
        out["mie"] = {"sigma_s": _rgb_list(_value(settings, "mie_sigma_s") / s),
                      "sigma_a": _rgb_list(_value(settings, "mie_sigma_a") / s),
                      "scale_height": _value(settings, "mie_scale_height") * s,
                      "phase": _phase(settings, "mie_phase", "mie_g")}
    if settings.use_ozone:
        out["ozone"] = {"sigma_a": _rgb_list(_value(settings, "ozone_sigma_a") / s),
                        "center_height": _value(settings, "ozone_center_height") * s,
                        "width": _value(settings, "ozone_width") * s}
    return out
