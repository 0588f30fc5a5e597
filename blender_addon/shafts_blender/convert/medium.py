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


def coefficients(output_node, what, warnings):
    """(sigma_s, sigma_a, phase) of the shader on an output node's Volume
    input, or None if it gives no medium."""
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
        warnings.add("%s has %d scattering lobes, whose phases Cycles sums; the scene's "
                     "medium scatters %d times their density with one Henyey-Greenstein "
                     "lobe of their mean g = %.4g." % (what, n, n, gmean))
    gmean = min(max(gmean, -G_MAX), G_MAX)
    phase = ({"type": "isotropic"} if gmean == 0.0
             else {"type": "henyey_greenstein", "g": float(gmean)})
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
