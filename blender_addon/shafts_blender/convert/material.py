"""Blender materials as the scene's Whitted materials.

The surface shader is read from the active Cycles material output as a sum
of closures (Add Shader, Mix Shader with a constant factor) with this table
(docs/blender.md, Mapping):

| Blender | scene | |
|---|---|---|
| no material | diffuse 0.8 (Cycles' default surface) | exact |
| nodes off | diffuse = the material's Color | exact |
| Diffuse BSDF, roughness 0 | diffuse = Color | exact (roughness > 0, Oren-Nayar: approximated as Lambert) |
| Glossy BSDF, Sharp or roughness < 0.01 | reflect = Color | exact |
| Glossy BSDF, rough | Phong: shininess n = (1/alpha^2 - 1)/2, alpha = roughness^2, specular = Color (n + 2)/(2 pi) | approximated |
| Transparent BSDF | transmit = Color, ior 1 | exact |
| Refraction BSDF, Sharp | transmit = Color, ior = IOR | exact |
| Glass BSDF | transmit = Color, reflect = Color F0(IOR), ior | approximated (Fresnel) |
| Emission | emission = Color Strength | exact when gated to traced rays as scene_export writes it; else approximated (it lights nothing) |
| Principled BSDF | diffuse = a (1-m)(1-t) B; specular layer S = a ((1-m) F0 + m B) as mirror (roughness < 0.01) or Phong; transmit = a (1-m) t B + (1-a), ior; emission | approximated (Fresnel, sheen, coat, subsurface dropped) |
| Mix Shader gated by Is Shadow Ray | the traced-ray branch | exact (the writer's straight shadows) |
| anything else | Lambert of its Color (or 0.8) | approximated |

B base colour, m metallic, t transmission, a alpha; F0 = 0.08 Specular
(3.x) or ((IOR - 1)/(IOR + 1))^2 2 Specular IOR Level (4.x). The Phong
exponent inverts scene_export's Glossy for a highlight, so a scene exported
to Blender and back keeps its shininess.
"""
import math

from . import nodes as nd

MIRROR_ROUGHNESS = 0.01
DEFAULT_GREY = [0.8, 0.8, 0.8]


class _Surface:
    def __init__(self, what, warnings):
        self.what, self.warnings = what, warnings
        self.diffuse = [0.0] * 3
        self.specular = [0.0] * 3
        self.shininess = None
        self.reflect = [0.0] * 3
        self.transmit = [0.0] * 3
        self.emission = [0.0] * 3
        self.ior = None
        self.seen_only = False

    def add(self, key, rgb, w):
        acc = getattr(self, key)
        for k in range(3):
            acc[k] += w * rgb[k]

    def glossy(self, rgb, roughness, w, node_name):
        if roughness < MIRROR_ROUGHNESS:
            self.add("reflect", rgb, w)
            return
        alpha = roughness * roughness
        n = max(0.0, (1.0 / (alpha * alpha) - 1.0) / 2.0)
        if self.shininess is not None and abs(self.shininess - n) > 1e-6 * n:
            self.warnings.add("%s has highlights of several roughnesses; the scene's Phong "
                              "highlight takes the first (shininess %.4g)."
                              % (self.what, self.shininess))
        else:
            self.shininess = n
        self.add("specular", [c * (n + 2.0) / (2.0 * math.pi) for c in rgb], w)
        self.warnings.add("%s has a rough glossy layer ('%s', roughness %.3g); it is a "
                          "Phong highlight of shininess %.4g with the same reflectance at "
                          "normal incidence." % (self.what, node_name, roughness, n))

    def set_ior(self, ior):
        if self.ior is not None and abs(self.ior - ior) > 1e-9:
            self.warnings.add("%s refracts with several IORs; the scene takes %g."
                              % (self.what, self.ior))
        elif ior > 0:
            self.ior = ior

    def result(self):
        out = {}
        for key in ("diffuse", "specular", "reflect", "transmit", "emission"):
            v = getattr(self, key)
            if any(x > 0 for x in v):
                out[key] = [max(0.0, float(x)) for x in v]
        if "specular" in out:
            out["shininess"] = float(self.shininess)
        if self.ior is not None and self.ior != 1.0:
            out["ior"] = float(self.ior)
        return out


def _fresnel0(ior):
    return ((ior - 1.0) / (ior + 1.0)) ** 2


def _principled(node, s, w):
    what, warn = s.what, s.warnings
    g = lambda names, default=0.0: nd.scalar(node, names, what, warn, default)
    base = nd.colour(node, ("Base Color",), what, warn)
    m = min(max(g(("Metallic",)), 0.0), 1.0)
    t = min(max(g(("Transmission", "Transmission Weight")), 0.0), 1.0)
    r = min(max(g(("Roughness",), 0.5), 0.0), 1.0)
    a = min(max(g(("Alpha",), 1.0), 0.0), 1.0)
    ior = g(("IOR",), 1.45)
    level = nd.find_input(node, "Specular IOR Level")
    if level is not None:  # Blender 4.x
        f0 = min(1.0, _fresnel0(ior) * 2.0 * g(("Specular IOR Level",), 0.5))
    else:
        f0 = 0.08 * g(("Specular",), 0.5)
    s.add("diffuse", base, w * a * (1 - m) * (1 - t))
    spec = [a * ((1 - m) * f0 + m * b) for b in base]
    if max(spec) > 0:
        s.glossy(spec, r, w, node.name)
    if t > 0 and m < 1:
        s.add("transmit", base, w * a * (1 - m) * t)
        s.set_ior(ior)
    if a < 1:
        s.add("transmit", [1.0, 1.0, 1.0], w * (1 - a))
    strength = g(("Emission Strength",), 1.0)
    emission = nd.colour(node, ("Emission", "Emission Color"), what, warn)
    if max(emission) > 0 and strength > 0:
        s.add("emission", emission, w * strength)
        if not s.seen_only:
            warn.add("%s emits light; the scene's emission is seen but lights nothing."
                     % what)
    dropped = [name for names, name in ((("Subsurface", "Subsurface Weight"), "subsurface"),
                                        (("Sheen", "Sheen Weight"), "sheen"),
                                        (("Clearcoat", "Coat Weight"), "coat"))
               if g(names) > 0]
    warn.add("%s is a Principled BSDF; it is mapped to Lambert, a %s and transmit by the "
             "table in docs/blender.md, without Fresnel%s."
             % (what, "mirror" if r < MIRROR_ROUGHNESS else "Phong highlight",
                (" or " + ", ".join(dropped)) if dropped else ""))


def _walk(node, socket, s, w, depth=0):
    what, warn = s.what, s.warnings
    if node is None or w == 0.0:
        return
    if depth > 64:
        warn.add("%s nests its shaders too deeply; the rest is left out." % what)
        return
    kind = node.bl_idname
    if kind == "ShaderNodeAddShader":
        for k in (0, 1):
            _walk(*nd.source(node.inputs[k]), s, w, depth + 1)
    elif kind == "ShaderNodeMixShader":
        fac = node.inputs[0]
        src, sock = nd.source(fac)
        if src is None:
            f = min(max(float(fac.default_value), 0.0), 1.0)
            _walk(*nd.source(node.inputs[1]), s, w * (1 - f), depth + 1)
            _walk(*nd.source(node.inputs[2]), s, w * f, depth + 1)
        elif src.bl_idname == "ShaderNodeLightPath" and sock.name == "Is Shadow Ray":
            _walk(*nd.source(node.inputs[1]), s, w, depth + 1)
        elif nd.is_light_path_gate(src, sock):
            seen, s.seen_only = s.seen_only, True
            _walk(*nd.source(node.inputs[2]), s, w, depth + 1)
            s.seen_only = seen
        else:
            warn.add("%s mixes shaders by '%s'; the scene takes half of each." % (what, src.name))
            _walk(*nd.source(node.inputs[1]), s, w * 0.5, depth + 1)
            _walk(*nd.source(node.inputs[2]), s, w * 0.5, depth + 1)
    elif kind == "ShaderNodeBsdfDiffuse":
        if nd.scalar(node, "Roughness", what, warn) > 0:
            warn.add("%s has a rough Diffuse BSDF (Oren-Nayar); it is rendered as Lambert."
                     % what)
        s.add("diffuse", nd.colour(node, "Color", what, warn), w)
    elif kind in ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfAnisotropic"):
        r = 0.0 if node.distribution == "SHARP" else nd.scalar(node, "Roughness", what, warn)
        s.glossy(nd.colour(node, "Color", what, warn), r, w, node.name)
    elif kind == "ShaderNodeBsdfTransparent":
        s.add("transmit", nd.colour(node, "Color", what, warn), w)
    elif kind in ("ShaderNodeBsdfRefraction", "ShaderNodeBsdfGlass"):
        c = nd.colour(node, "Color", what, warn)
        ior = nd.scalar(node, "IOR", what, warn, 1.45)
        r = 0.0 if node.distribution == "SHARP" else nd.scalar(node, "Roughness", what, warn)
        if r > 0:
            warn.add("%s has rough refraction ('%s', roughness %.3g); it is rendered "
                     "sharp." % (what, node.name, r))
        s.add("transmit", c, w)
        s.set_ior(ior)
        if kind == "ShaderNodeBsdfGlass":
            s.add("reflect", c, w * _fresnel0(ior))
            warn.add("%s is a Glass BSDF; it is transmit with IOR %g plus a mirror of "
                     "its normal-incidence Fresnel reflectance %.3g (the scene's weights do "
                     "not vary with the angle)." % (what, ior, _fresnel0(ior)))
    elif kind == "ShaderNodeEmission":
        c = nd.colour(node, "Color", what, warn)
        strength = nd.scalar(node, "Strength", what, warn, 1.0)
        s.add("emission", c, w * strength)
        if not s.seen_only and max(c) * strength > 0:
            warn.add("%s emits light; the scene's emission is seen but lights nothing."
                     % what)
    elif kind == "ShaderNodeBsdfPrincipled":
        _principled(node, s, w)
    elif kind == "ShaderNodeHoldout":
        warn.add("%s has a Holdout; it is rendered black." % what)
    else:
        c = nd.colour(node, "Color", what, warn) if "Color" in node.inputs else DEFAULT_GREY
        warn.add("%s uses a '%s' node, which the scene has no counterpart for; it is "
                 "rendered as a Lambert surface of its colour." % (what, node.name))
        s.add("diffuse", c, w)


def surface_output(mat):
    """The active Cycles material output node, or None."""
    tree = mat.node_tree
    if tree is None:
        return None
    out = None
    if hasattr(tree, "get_output_node"):
        out = tree.get_output_node("CYCLES")
    if out is None:
        out = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"
                    and n.is_active_output), None)
    return out


def export_material(mat, warnings):
    """The format's material object for a Blender material (None: Cycles'
    default surface). The add-on's soft-shadow settings of the material
    (material.shafts, properties.py) give the light meshes method's
    "casts_soft_shadows" and "receives_soft_shadows" keys, written when off."""
    out = _material(mat, warnings)
    settings = getattr(mat, "shafts", None)
    for key in ("casts_soft_shadows", "receives_soft_shadows"):
        if settings is not None and not getattr(settings, key):
            out[key] = False
    return out


def _material(mat, warnings):
    if mat is None:
        return {"diffuse": list(DEFAULT_GREY)}
    what = "The material '%s'" % mat.name
    if not mat.use_nodes or mat.node_tree is None:
        return {"diffuse": [max(0.0, float(x)) for x in mat.diffuse_color[:3]]}
    out = surface_output(mat)
    s = _Surface(what, warnings)
    if out is not None:
        _walk(*nd.source(out.inputs["Surface"]), s, 1.0)
    return s.result()


def has_volume(mat):
    out = surface_output(mat) if mat is not None and mat.use_nodes else None
    return out is not None and out.inputs["Volume"].is_linked


def has_surface(mat):
    if mat is None or not mat.use_nodes:
        return True
    out = surface_output(mat)
    return out is not None and out.inputs["Surface"].is_linked
