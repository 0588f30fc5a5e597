"""Blender lights as the scene's lights, with Cycles' conventions.

Cycles 3.4 (intern/cycles/kernel/light/, blender/light.cpp; the facts in
/work/shared/notes/renderer-semantics.md, verified by renders in
docs/scene_export.md):

- Point light of power P watts and colour c: radiant intensity
  I = c P / (4 pi) W/sr in every direction.
- Spot light: the same I on its axis; spot_size is the full cone angle, so
  outer = spot_size / 2; Cycles' spot_attenuation is
  cos(theta) * smoothstep((cos theta - c0) / ((1 - c0) spot_blend)),
  c0 = cos(outer): the format's exponent 1 with
  cos(inner) = c0 + (1 - c0) spot_blend.
- Sun of strength S and colour c: irradiance c S W/m^2 normal to its
  direction.
- Lights point along their object's -Z axis.

A light's node tree (use_nodes) is read when its output is one Emission
whose Color and Strength multiply the light (exact); an Image Texture on the
Color of a spot becomes the spot's light map (approximated: the format
projects the image over the cone's square, top towards the light's +Y).
Approximated with a warning: a radius or sun angle (rendered as a point or a
parallel light), no shadows, area lights (a Lambertian point emitter: a spot
with outer = inner = 90 degrees and exponent 1 and Cycles' axial intensity,
AREA_INTENSITY_PER_WATT), non-uniformly scaled spot cones, other node
set-ups.
"""
import math

import numpy as np

from . import coords

# Radiant intensity on the axis of a Cycles area light per watt of power:
# Cycles gives an area light of power P the radiance P / (4 A), so its
# intensity on the axis is L A = P / 4. Measured with Cycles 3.4 by
# blender_addon/convert_tests/area_power.py (docs/blender.md, Mapping): a
# 5 cm square light of 100 W, 2 m above a white Lambert floor, gives
# I = 24.98 W/sr (point light of 100 W: 7.956 = 100 / (4 pi)).
AREA_INTENSITY_PER_WATT = 0.25


def _axis(m, column):
    return np.asarray(coords.matrix_array(m)[:3, column])


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    n = np.linalg.norm(v)
    return [float(x) for x in (v / n if n > 0 else np.array([0.0, 0.0, -1.0]))]


def _node_colour(light, what, warnings):
    """The colour factor of a light's node tree and the image of a gobo (or
    None): (rgb, image)."""
    if not light.use_nodes or light.node_tree is None:
        return (1.0, 1.0, 1.0), None
    tree = light.node_tree
    out = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputLight"
                and n.is_active_output), None)
    if out is None or not out.inputs["Surface"].is_linked:
        return (1.0, 1.0, 1.0), None
    node = out.inputs["Surface"].links[0].from_node
    if node.bl_idname != "ShaderNodeEmission":
        warnings.add("%s uses a '%s' node for its emission; it is rendered with its "
                     "colour and power alone." % (what, node.name))
        return (1.0, 1.0, 1.0), None
    strength = node.inputs["Strength"]
    if strength.is_linked:
        warnings.add("%s has a linked emission Strength; it is taken as 1." % what)
        s = 1.0
    else:
        s = float(strength.default_value)
    colour = node.inputs["Color"]
    image = None
    if colour.is_linked:
        src = colour.links[0].from_node
        if src.bl_idname == "ShaderNodeTexImage" and src.image is not None:
            image = src.image
            c = (s, s, s)
        else:
            warnings.add("%s has a linked emission Color from '%s'; it is taken as "
                         "white." % (what, src.name))
            c = (s, s, s)
    else:
        c = tuple(float(x) * s for x in colour.default_value[:3])
    return c, image


def _image_path(image):
    import bpy
    if image.source != "FILE" or not image.filepath:
        return None
    return bpy.path.abspath(image.filepath, library=image.library)


def export_light(obj, matrix_world, warnings):
    """The format's light object for one evaluated light instance, or None
    if the light gives no light. The add-on's Soft Shadows setting of the
    light (light.shafts, properties.py) gives the light meshes method's
    "soft_shadows" key, written when off."""
    out = _light(obj, matrix_world, warnings)
    settings = getattr(obj.data, "shafts", None)
    if out is not None and settings is not None and not settings.soft_shadows:
        out["soft_shadows"] = False
    return out


def _light(obj, matrix_world, warnings):
    light = obj.data
    what = "The light '%s'" % obj.name
    m = coords.matrix_array(matrix_world)
    position = coords.vector(m[:3, 3])
    direction = _unit(coords.vector(-_axis(m, 2)))
    factor, image = _node_colour(light, what, warnings)
    colour = [float(c) * f for c, f in zip(light.color, factor)]
    energy = float(light.energy)
    if energy < 0 or min(colour) < 0:
        warnings.add("%s has a negative power or colour (it removes light in Cycles); "
                     "the scene's lights cannot, so it gives none." % what)
        energy, colour = max(energy, 0.0), [max(c, 0.0) for c in colour]
    cycles = getattr(light, "cycles", None)
    if cycles is not None and not getattr(cycles, "cast_shadow", True):
        warnings.add("%s casts no shadows in Cycles; the scene's lights always cast "
                     "shadows and are attenuated by the medium." % what)
    kind = light.type
    if kind == "SUN":
        if light.angle > 0:
            warnings.add("%s has an angular diameter of %.3g degrees; it is rendered as "
                         "a parallel light (sharp shadows)." % (what, math.degrees(light.angle)))
        if image is not None:
            warnings.add("%s has an image on its colour; a sun's pattern is not "
                         "exported (the format's window needs a placement)." % what)
        return {"type": "directional", "direction": direction,
                "irradiance": [c * energy for c in colour]}
    if kind in ("POINT", "SPOT") and light.shadow_soft_size > 0:
        warnings.add("%s has a radius of %.3g; it is rendered as a point light (sharp "
                     "shadows, the same power)." % (what, light.shadow_soft_size))
    if kind == "POINT":
        if image is not None:
            warnings.add("%s has an image on its colour; point lights take no light map "
                         "in the format, so it is ignored." % what)
        return {"type": "point", "position": position,
                "intensity": [c * energy / (4.0 * math.pi) for c in colour]}
    if kind == "SPOT":
        outer = 0.5 * float(light.spot_size)
        c0 = math.cos(outer)
        inner = math.acos(min(1.0, c0 + (1.0 - c0) * float(light.spot_blend)))
        sx, sy = np.linalg.norm(m[:3, 0]), np.linalg.norm(m[:3, 1])
        if abs(sx - sy) > 1e-6 * max(sx, sy):
            warnings.add("%s is scaled unevenly, which makes its cone elliptical in "
                         "Blender; it is rendered with a round cone of spot size %.4g "
                         "degrees." % (what, math.degrees(light.spot_size)))
        out = {"type": "spot", "position": position, "direction": direction,
               "intensity": [c * energy / (4.0 * math.pi) for c in colour],
               "outer_angle_deg": math.degrees(outer),
               "inner_angle_deg": min(math.degrees(inner), math.degrees(outer)),
               "exponent": 1.0}
        if image is not None:
            path = _image_path(image)
            if path is None or outer >= math.radians(89.999):
                warnings.add("%s has an image on its colour that cannot be a light map "
                             "(%s); it is rendered without it."
                             % (what, "no image file" if path is None
                                else "the cone is 180 degrees or wider"))
            else:
                warnings.add("%s projects the image '%s' as the format's gobo: over the "
                             "square of the cone at unit distance, its top towards the "
                             "light's +Y; Cycles maps it by the node set-up."
                             % (what, image.name))
                out["light_map"] = {"image": path,
                                    "up": _unit(coords.vector(_axis(m, 1)))}
        return out
    if kind == "AREA":
        warnings.add("%s is an area light (%s, %.3g x %.3g); it is rendered as a "
                     "Lambertian point emitter at its centre (a spot of 90 degrees, "
                     "exponent 1, the same axial intensity), so its shadows are sharp."
                     % (what, light.shape.lower(), light.size,
                        light.size_y if light.shape in ("RECTANGLE", "ELLIPSE") else light.size))
        spread = getattr(light, "spread", math.pi)
        if spread < math.pi - 1e-6:
            warnings.add("%s has a spread of %.4g degrees; the scene's emitter is "
                         "Lambertian (a spread of 180)." % (what, math.degrees(spread)))
        return {"type": "spot", "position": position, "direction": direction,
                "intensity": [c * energy * AREA_INTENSITY_PER_WATT for c in colour],
                "outer_angle_deg": 90.0, "inner_angle_deg": 90.0, "exponent": 1.0}
    warnings.add("%s is of type %s, which the scene format has no counterpart for; it "
                 "is left out." % (what, kind))
    return None
