# Blender 3.4 loader for a scene exported by scene_export (--to blender).
#
# One converter, two uses: scene_export embeds this file and writes it next
# to every Blender export as NAME.py (the fixed script), and the add-on
# imports it as a module (shafts_blender.convert.blender_build) for File >
# Import > Shafts scene, which gets the same data from the same C writer
# through libshafts.so (importer.py, scene_export/se_run.h). As a module it
# only defines functions (build_into adds a scene's objects to a
# collection); run as a script it renders.
#
# This file is the same for every scene: the scene lives in the JSON file
# next to it (same name, .blender.json), which is read with json.load and only ever
# used as data. Render with
#
#   blender -b -P NAME.py -- --engine cycles|eevee --out IMG.exr
#           [--samples N] [--seed S] [--width W] [--height H] [--one-pass]
#
# (--width/--height as scene_export's: the image size instead of the
# data's, the other side following the aspect unless given, the vertical
# field of view kept.)
# (EEVEE needs an OpenGL context: run it under xvfb-run.) The image is
# linear radiance, 32-bit float OpenEXR, one sample position per pixel
# centre. Cycles 3.4 renders a ray-marched (height fog, atmosphere) medium
# whose coefficients differ between colour channels too dark (it picks the
# channel it samples distances in from one random number per path, at
# every step: docs/scene_export.md, "The atmosphere in Cycles"), so the
# script renders such a scene once per channel with grey coefficients and
# composes channel c of pass c into the image (--one-pass: one render, as
# Cycles does it). Exit status: 0 on success, 2 for bad arguments or data, 1 if
# rendering fails. See docs/scene_export.md for what is exact and what is
# approximated.
import array
import json
import math
import os
import shutil
import sys
import tempfile

import bpy
from mathutils import Matrix

USAGE = ("usage: blender -b -P NAME.py -- --engine cycles|eevee --out IMG.exr "
         "[--samples N] [--seed S] [--width W] [--height H] [--one-pass]")

# The bounds of --samples and --seed: Cycles' own (its samples property
# holds 1 to 2^24, its seed 0 to 2^31 - 1; EEVEE's samples as many).
SAMPLES_MAX = 16777216
SEED_MAX = 2147483647

HELP = USAGE + """

Renders the scene exported next to this script (NAME.blender.json) into
IMG.exr: linear radiance as 32-bit float OpenEXR, one sample position per
pixel centre.

  --engine cycles|eevee  the renderer (default: cycles); EEVEE needs a
                         display: run it under xvfb-run
  --out IMG.exr          the image, required; it must end in .exr and its
                         directory must exist and be writable (checked
                         before the scene is built)
  --samples N            samples per pixel, 1 to %d (default: the
                         export's, --quality draft 64 for Cycles and 16 for
                         EEVEE)
  --seed S               Cycles' random seed, 0 to %d (default: the
                         export's)
  --width W, --height H  the image size, 1 to 65536 (default: the export's;
                         one alone keeps the aspect)
  --one-pass             Cycles: render a ray-marched medium whose
                         coefficients differ between colour channels in one
                         pass, as Cycles does (default: once per channel,
                         composed)

exit status: 0 success (the image written), 1 building or rendering
failed, 2 bad arguments or data (nothing written).""" % (SAMPLES_MAX, SEED_MAX)


class DataError(Exception):
    """The arguments or the JSON data are not what the exporter writes."""


def json_object(value, what, optional=False):
    """value checked to be a JSON object (None as well if optional), else
    DataError naming what."""
    if value is None and optional:
        return None
    if not isinstance(value, dict):
        raise DataError(what + ": expected an object")
    return value


def parse_args(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    opts = {"engine": "cycles", "out": None, "samples": None, "seed": None,
            "width": None, "height": None, "one_pass": False}
    i = 0
    while i < len(args):
        key = args[i]
        if key in ("-h", "--help"):
            print(HELP)
            sys.exit(0)
        if key == "--one-pass":
            opts["one_pass"] = True
            i += 1
            continue
        if key not in ("--engine", "--out", "--samples", "--seed", "--width",
                       "--height") or i + 1 >= len(args):
            raise DataError("unknown or incomplete option %r; %s" % (key, USAGE))
        value = args[i + 1]
        if key == "--engine":
            if value not in ("cycles", "eevee"):
                raise DataError("--engine expects cycles or eevee, got %r" % value)
            opts["engine"] = value
        elif key == "--out":
            check_out(value)
            opts["out"] = os.path.abspath(value)
        elif key in ("--width", "--height"):
            # As scene_export and the renderers word it (core/sh_cli.h).
            if not (value.isascii() and value.isdigit()) or not 1 <= int(value) <= 65536:
                raise DataError("%s: expected an integer from 1 to 65536, found '%s'"
                                % (key, value))
            opts[key[2:]] = int(value)
        else:
            low, high = (1, SAMPLES_MAX) if key == "--samples" else (0, SEED_MAX)
            if not (value.isascii() and value.isdigit()) or not low <= int(value) <= high:
                raise DataError("%s: expected an integer from %d to %d, found '%s'"
                                % (key, low, high, value))
            opts[key[2:]] = int(value)
        i += 2
    if not opts["out"]:
        raise DataError("--out IMG.exr is required; " + USAGE)
    return opts


def check_out(path):
    """--out checked before any work, worded as the C tools' -o
    (core/sh_cli.c): it ends in .exr, and its directory exists and takes a
    new file (a file made and removed there: permissions alone do not say,
    for root or a read-only mount). DataError otherwise."""
    if not path.lower().endswith(".exr") or os.path.basename(path) == ".exr":
        raise DataError("--out '%s' must end in .exr (the image is 32-bit float OpenEXR)"
                        % path)
    directory = os.path.dirname(path) or "."
    if not os.path.exists(directory):
        raise DataError("--out: directory '%s' does not exist" % directory)
    try:
        fd, probe = tempfile.mkstemp(prefix=".shafts-probe-", dir=directory)
        os.close(fd)
        os.unlink(probe)
    except OSError:
        raise DataError("--out: '%s' is not a directory this user can write to"
                        % directory) from None


def numbers(value, count=None, what="value"):
    if not isinstance(value, list) or (count is not None and len(value) != count):
        raise DataError("%s: expected a list of %s numbers" % (what, count or "some"))
    for v in value:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise DataError("%s: expected numbers" % what)
    return [float(v) for v in value]


def rgb(value, what):
    return tuple(numbers(value, 3, what)) + (1.0,)


def matrix(value, what):
    m = numbers(value, 16, what)
    return Matrix([m[0:4], m[4:8], m[8:12], m[12:16]])


def new_object(name, data, collection):
    obj = bpy.data.objects.new(name, data)
    collection.objects.link(obj)
    return obj


def build_mesh(name, item, what):
    verts = numbers(item.get("vertices"), None, what + ".vertices")
    tris = item.get("triangles")
    if len(verts) % 3 or not isinstance(tris, list) or len(tris) % 3:
        raise DataError(what + ": vertices and triangles must come in threes")
    nverts = len(verts) // 3
    for t in tris:
        if isinstance(t, bool) or not isinstance(t, int) or not 0 <= t < nverts:
            raise DataError(what + ": a triangle index is out of range")
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(verts[i:i + 3]) for i in range(0, len(verts), 3)], [],
                     [tuple(tris[i:i + 3]) for i in range(0, len(tris), 3)])
    mesh.validate(clean_customdata=False)
    mesh.update()
    return mesh


def set_if(owner, attr, value):
    """Sets a property that Blender 3.4 has and a later version may have
    dropped (the script targets 3.4; the add-on's import should still build
    on 4.x, where it can)."""
    if owner is not None and hasattr(owner, attr):
        setattr(owner, attr, value)


def set_sharp(bsdf):
    """A sharp Glossy or Refraction BSDF: the SHARP distribution (3.x), or
    GGX at roughness 0 where SHARP is gone (4.x)."""
    try:
        bsdf.distribution = "SHARP"
    except TypeError:
        bsdf.distribution = "GGX"
        bsdf.inputs["Roughness"].default_value = 0.0


def node(tree, kind, **inputs):
    n = tree.nodes.new(kind)
    for key, value in inputs.items():
        n.inputs[key].default_value = value
    return n


def add_all(tree, shaders):
    """The sum of several shader outputs (None if there are none)."""
    total = None
    for s in shaders:
        if total is None:
            total = s
        else:
            add = tree.nodes.new("ShaderNodeAddShader")
            tree.links.new(total, add.inputs[0])
            tree.links.new(s, add.inputs[1])
            total = add.outputs[0]
    return total


def _op(tree, kind, operation, *args):
    """A Math or Vector Math node of `operation` on its arguments (output
    sockets are linked, numbers and tuples set as values); its output."""
    n = tree.nodes.new(kind)
    n.operation = operation
    for k, a in enumerate(args):
        if hasattr(a, "is_output"):
            tree.links.new(a, n.inputs[k])
        else:
            n.inputs[k].default_value = a
    return n.outputs["Value" if kind == "ShaderNodeMath" else
                     ("Value" if operation in ("LENGTH", "DOT", "DISTANCE") else "Vector")]


def smath(tree, operation, *args):
    return _op(tree, "ShaderNodeMath", operation, *args)


def vmath(tree, operation, *args):
    return _op(tree, "ShaderNodeVectorMath", operation, *args)


def light_transmittance(tree, t):
    """The transmittance, per channel, from the shading point P to the
    light through the medium's box: exp(-sigma_t L), L the length of the
    segment P -> P + d inside the box (slab test), d = light position - P
    (point, spot) or a long step towards a sun. EEVEE lights surfaces as if
    no medium were there; this is the factor it leaves out. In height fog
    (t["fog"]) L is the integral of the density factor along the segment
    inside the box, rho(z_low) L_box (1 - exp(-x)) / x with z_low the
    inside part's lower end and x = |dz| (t1 - t0) / H (the core's
    cancellation-free form; x is kept above 1e-3, an error of at most
    5e-4 of the optical depth, where single precision would cancel)."""
    pos = tree.nodes.new("ShaderNodeNewGeometry").outputs["Position"]
    # A tiny offset keeps every component of d away from 0, where Blender's
    # safe division gives 0 instead of +-infinity.
    eps = (t["eps"],) * 3
    if t["position"] is None:
        d = vmath(tree, "ADD", tuple(x + t["eps"] for x in t["towards"]), (0.0, 0.0, 0.0))
    else:
        d = vmath(tree, "ADD", vmath(tree, "SUBTRACT", t["position"], pos), eps)
    ta = vmath(tree, "DIVIDE", vmath(tree, "SUBTRACT", t["lo"], pos), d)
    tb = vmath(tree, "DIVIDE", vmath(tree, "SUBTRACT", t["hi"], pos), d)
    near = tree.nodes.new("ShaderNodeSeparateXYZ")
    far = tree.nodes.new("ShaderNodeSeparateXYZ")
    tree.links.new(vmath(tree, "MINIMUM", ta, tb), near.inputs[0])
    tree.links.new(vmath(tree, "MAXIMUM", ta, tb), far.inputs[0])
    t0 = smath(tree, "MAXIMUM", smath(tree, "MAXIMUM", near.outputs[0], near.outputs[1]),
              smath(tree, "MAXIMUM", near.outputs[2], 0.0))
    t1 = smath(tree, "MINIMUM", smath(tree, "MINIMUM", far.outputs[0], far.outputs[1]),
              smath(tree, "MINIMUM", far.outputs[2], 1.0))
    inside = smath(tree, "MULTIPLY", smath(tree, "MAXIMUM", smath(tree, "SUBTRACT", t1, t0), 0.0),
                  vmath(tree, "LENGTH", d))
    fog = t.get("fog")
    if fog is not None:
        dxyz = tree.nodes.new("ShaderNodeSeparateXYZ")
        pxyz = tree.nodes.new("ShaderNodeSeparateXYZ")
        tree.links.new(d, dxyz.inputs[0])
        tree.links.new(pos, pxyz.inputs[0])
        dz = dxyz.outputs["Z"]
        span = smath(tree, "MAXIMUM", smath(tree, "SUBTRACT", t1, t0), 0.0)
        z0 = smath(tree, "ADD", pxyz.outputs["Z"], smath(tree, "MULTIPLY", t0, dz))
        z1 = smath(tree, "ADD", pxyz.outputs["Z"], smath(tree, "MULTIPLY", t1, dz))
        below = smath(tree, "SUBTRACT", fog["bottom"], smath(tree, "MINIMUM", z0, z1))
        rho = smath(tree, "EXPONENT", smath(tree, "DIVIDE", below, fog["scale_height"]))
        rise = smath(tree, "MULTIPLY", span, smath(tree, "ABSOLUTE", dz))
        x = smath(tree, "MAXIMUM", smath(tree, "DIVIDE", rise, fog["scale_height"]), 1e-3)
        g = smath(tree, "DIVIDE", smath(tree, "SUBTRACT", 1.0, smath(
            tree, "EXPONENT", smath(tree, "MULTIPLY", x, -1.0))), x)
        inside = smath(tree, "MULTIPLY", smath(tree, "MULTIPLY", inside, rho), g)
    rgb_out = tree.nodes.new("ShaderNodeCombineXYZ")
    for c in range(3):
        tau = smath(tree, "MULTIPLY", inside, -t["sigma_t"][c])
        tree.links.new(smath(tree, "EXPONENT", tau), rgb_out.inputs[c])
    return rgb_out.outputs[0]


def tinted(tree, colour, factor):
    """A colour socket value times a factor socket (None: the colour)."""
    if factor is None:
        return None
    return vmath(tree, "MULTIPLY", colour[:3], factor)


def transmittance_setup(data, engine):
    """What light_transmittance needs, or None: EEVEE, a medium that
    extinguishes and exactly one light (with several, EEVEE's surfaces stay
    unattenuated: the data's eevee_notes say so)."""
    lights = data.get("lights", [])
    if engine != "eevee" or "medium" not in data or len(lights) != 1:
        return None
    m = data["medium"]
    sigma_t = numbers(m.get("sigma_t"), 3, "medium.sigma_t")
    if max(sigma_t) <= 0:
        return None
    lo = numbers(m.get("min"), 3, "medium.min")
    hi = numbers(m.get("max"), 3, "medium.max")
    mat = matrix(lights[0].get("matrix"), "lights[0].matrix")
    far = 10.0 * numbers([data.get("camera", {}).get("clip_end")], 1, "camera.clip_end")[0]
    t = {"lo": tuple(lo), "hi": tuple(hi), "sigma_t": sigma_t, "eps": 1e-9 * far,
         "position": None, "towards": None, "fog": fog_setup(m)}
    if lights[0].get("type") == "SUN":
        z = mat.col[2]
        t["towards"] = (z[0] * far, z[1] * far, z[2] * far)
    else:
        t["position"] = tuple(mat.translation)
    return t


def sun_disks(tree, world):
    """The background radiance plus the sun's disks (docs/scene-format.md,
    "The sun's disk") as a colour socket, or None without disks: each
    disk's radiance where the world direction (Generated, a unit vector in
    world shaders) lies within `chord` of the direction towards the sun,
    |d - s| < chord = 2 sin(half angle / 2), which keeps its digits in
    single precision where a cosine test would not."""
    disks = world.get("sun_disks", [])
    if not isinstance(disks, list):
        raise DataError("world.sun_disks: expected a list")
    if not disks:
        return None
    direction = tree.nodes.new("ShaderNodeTexCoord").outputs["Generated"]
    total = node(tree, "ShaderNodeCombineXYZ")
    for k, v in zip("XYZ", rgb(world.get("background"), "world.background")):
        total.inputs[k].default_value = v
    total = total.outputs[0]
    for i, d in enumerate(disks):
        what = "world.sun_disks[%d]" % i
        json_object(d, what)
        dist = tree.nodes.new("ShaderNodeVectorMath")
        dist.operation = "DISTANCE"
        tree.links.new(direction, dist.inputs[0])
        dist.inputs[1].default_value = numbers(d.get("direction"), 3, what + ".direction")
        inside = tree.nodes.new("ShaderNodeMath")
        inside.operation = "LESS_THAN"
        tree.links.new(dist.outputs["Value"], inside.inputs[0])
        inside.inputs[1].default_value = numbers([d.get("chord")], 1, what + ".chord")[0]
        scale = tree.nodes.new("ShaderNodeVectorMath")
        scale.operation = "SCALE"
        scale.inputs[0].default_value = numbers(d.get("radiance"), 3, what + ".radiance")
        tree.links.new(inside.outputs[0], scale.inputs["Scale"])
        add = tree.nodes.new("ShaderNodeVectorMath")
        add.operation = "ADD"
        tree.links.new(total, add.inputs[0])
        tree.links.new(scale.outputs["Vector"], add.inputs[1])
        total = add.outputs["Vector"]
    return total


def seen_by_traced_rays(tree):
    """A factor that is 1 for camera, glossy and transmission rays and 0 for
    diffuse and volume-scatter rays: emission, the ambient term and the
    background are radiance to be seen, never light that illuminates (the
    Whitted model has no interreflection)."""
    path = tree.nodes.new("ShaderNodeLightPath")
    a = tree.nodes.new("ShaderNodeMath")
    a.operation = "MAXIMUM"
    tree.links.new(path.outputs["Is Camera Ray"], a.inputs[0])
    tree.links.new(path.outputs["Is Glossy Ray"], a.inputs[1])
    b = tree.nodes.new("ShaderNodeMath")
    b.operation = "MAXIMUM"
    tree.links.new(a.outputs[0], b.inputs[0])
    tree.links.new(path.outputs["Is Transmission Ray"], b.inputs[1])
    return b.outputs[0]


def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    return mat, tree, out


def surface_material(item, index, transmittance=None):
    """The Whitted material as a sum of closures: Diffuse (Lambert), Glossy
    (the Phong highlight, approximate), sharp Glossy (mirror), Refraction for
    traced rays with Transparent for shadow rays (transmit), Emission (with
    the ambient term) seen by traced rays only, so that it lights nothing.
    With `transmittance` (transmittance_setup), the diffuse and glossy
    colours are multiplied by the light's transmittance through the medium
    (for EEVEE, which leaves it out)."""
    what = "materials[%d]" % index
    mat, tree, out = new_material("material%d %s" % (index, str(item.get("label", ""))[:40]))
    set_if(mat.cycles, "sample_as_light", False)
    set_if(mat.cycles, "emission_sampling", "NONE")
    path = tree.nodes.new("ShaderNodeLightPath")
    parts = []
    factor = (light_transmittance(tree, transmittance) if transmittance is not None
              else None)
    diffuse = rgb(item.get("diffuse"), what + ".diffuse")
    if max(diffuse[:3]) > 0:
        d = node(tree, "ShaderNodeBsdfDiffuse", Color=diffuse, Roughness=0.0)
        if factor is not None:
            tree.links.new(tinted(tree, diffuse, factor), d.inputs["Color"])
        parts.append(d.outputs[0])
    if "glossy" in item:
        glossy = rgb(item["glossy"], what + ".glossy")
        g = node(tree, "ShaderNodeBsdfGlossy", Color=glossy,
                 Roughness=numbers([item.get("roughness")], 1, what + ".roughness")[0])
        g.distribution = "BECKMANN"
        if factor is not None:
            tree.links.new(tinted(tree, glossy, factor), g.inputs["Color"])
        parts.append(g.outputs[0])
    mirror = rgb(item.get("mirror"), what + ".mirror")
    if max(mirror[:3]) > 0:
        g = node(tree, "ShaderNodeBsdfGlossy", Color=mirror, Roughness=0.0)
        set_sharp(g)
        parts.append(g.outputs[0])
    transmit = rgb(item.get("transmit"), what + ".transmit")
    ior = numbers([item.get("ior")], 1, what + ".ior")[0]
    if max(transmit[:3]) > 0:
        clear = node(tree, "ShaderNodeBsdfTransparent", Color=transmit)
        if ior == 1.0:
            parts.append(clear.outputs[0])
        else:
            refr = node(tree, "ShaderNodeBsdfRefraction", Color=transmit, Roughness=0.0, IOR=ior)
            set_sharp(refr)
            mix = tree.nodes.new("ShaderNodeMixShader")
            tree.links.new(path.outputs["Is Shadow Ray"], mix.inputs["Fac"])
            tree.links.new(refr.outputs[0], mix.inputs[1])
            tree.links.new(clear.outputs[0], mix.inputs[2])
            parts.append(mix.outputs[0])
        set_if(mat, "blend_method", "HASHED")
        set_if(mat, "shadow_method", "HASHED")
        set_if(mat, "use_screen_refraction", ior != 1.0)
    emission = rgb(item.get("emission"), what + ".emission")
    if max(emission[:3]) > 0:
        e = node(tree, "ShaderNodeEmission", Color=emission, Strength=1.0)
        mix = tree.nodes.new("ShaderNodeMixShader")
        tree.links.new(seen_by_traced_rays(tree), mix.inputs["Fac"])
        tree.links.new(e.outputs[0], mix.inputs[2])
        parts.append(mix.outputs[0])
    total = add_all(tree, parts)
    if total is not None:
        tree.links.new(total, out.inputs["Surface"])
    else:  # a black, opaque surface
        tree.links.new(node(tree, "ShaderNodeBsdfDiffuse", Color=(0, 0, 0, 1)).outputs[0],
                       out.inputs["Surface"])
    return mat


def card_material(item, images, index):
    """A filter card: transparent, coloured by the light map (or black, for
    the wall around a window), for shadow rays; fully clear for any other
    ray, so that only light passing it is filtered."""
    what = "cards[%d]" % index
    mat, tree, out = new_material("card%d" % index)
    path = tree.nodes.new("ShaderNodeLightPath")
    filt = tree.nodes.new("ShaderNodeBsdfTransparent")
    image = item.get("image")
    if isinstance(image, bool) or not isinstance(image, int) or not -1 <= image < len(images):
        raise DataError(what + ".image: expected an image index or -1")
    if image >= 0:
        tex = tree.nodes.new("ShaderNodeTexImage")
        tex.image = images[image]
        tex.interpolation = "Linear"
        tex.extension = "EXTEND"
        tree.links.new(tex.outputs["Color"], filt.inputs["Color"])
    else:
        filt.inputs["Color"].default_value = (0, 0, 0, 1)
    clear = node(tree, "ShaderNodeBsdfTransparent", Color=(1, 1, 1, 1))
    mix = tree.nodes.new("ShaderNodeMixShader")
    tree.links.new(path.outputs["Is Shadow Ray"], mix.inputs["Fac"])
    tree.links.new(clear.outputs[0], mix.inputs[1])
    tree.links.new(filt.outputs[0], mix.inputs[2])
    tree.links.new(mix.outputs[0], out.inputs["Surface"])
    set_if(mat, "blend_method", "HASHED")
    set_if(mat, "shadow_method", "HASHED")
    return mat


def fog_setup(item):
    """The medium's "height_fog" data checked, or None for a homogeneous
    medium: the coefficients written are those at the box's bottom z_lo,
    and the density factor at a point of Blender height z is
    exp((z_lo - z) / H)."""
    f = json_object(item.get("height_fog"), "medium.height_fog", optional=True)
    if f is None:
        return None
    what = "medium.height_fog."
    fog = {k: numbers([f.get(k)], 1, what + k)[0]
           for k in ("bottom", "scale_height", "step_rate", "max_steps")}
    if not (fog["scale_height"] > 0 and fog["step_rate"] > 0 and fog["max_steps"] >= 1):
        raise DataError("medium.height_fog: scale_height, step_rate and max_steps "
                        "must be above 0")
    fog["max_steps"] = int(fog["max_steps"])
    return fog


def fog_density(tree, fog, density):
    """A socket giving density * exp((z_lo - z) / H) at the shading point
    (Geometry > Position; Blender's Z is the scene's height)."""
    pos = tree.nodes.new("ShaderNodeNewGeometry").outputs["Position"]
    xyz = tree.nodes.new("ShaderNodeSeparateXYZ")
    tree.links.new(pos, xyz.inputs[0])
    below = smath(tree, "SUBTRACT", fog["bottom"], xyz.outputs["Z"])
    rho = smath(tree, "EXPONENT", smath(tree, "DIVIDE", below, fog["scale_height"]))
    return smath(tree, "MULTIPLY", rho, density)


def volume_material(item, engine):
    """The medium, no surface: one Principled Volume (Color, Density,
    Absorption Color, Anisotropy as the writer computed them, so that its
    sigma_s, sigma_a and Henyey-Greenstein g are the scene's in both
    engines), or, for Cycles when the data holds a mixture of lobes
    ("cycles_mixture"), Volume Scatter lobes plus Volume Absorption joined
    by Add Shaders (Cycles sums their phases; EEVEE would average their g,
    so it keeps the single lobe). Height fog ("height_fog") multiplies
    every Density by its node graph (fog_density); Cycles then ray-marches
    the material at the data's step rate (setup_render raises the scene's
    volume_max_steps to the data's)."""
    mat, tree, out = new_material("medium")
    fog = fog_setup(item)
    set_if(mat.cycles, "homogeneous_volume", fog is None)
    set_if(mat.cycles, "volume_sampling", "MULTIPLE_IMPORTANCE")
    if fog is not None:
        set_if(mat.cycles, "volume_step_rate", fog["step_rate"])

    def volume(kind, value, **inputs):
        n = node(tree, kind, **inputs)
        if fog is None:
            n.inputs["Density"].default_value = value
        else:
            tree.links.new(fog_density(tree, fog, value), n.inputs["Density"])
        return n

    mix = item.get("cycles_mixture")
    if engine == "cycles" and mix is not None:
        if not isinstance(mix, dict) or not isinstance(mix.get("scatter"), list):
            raise DataError("medium.cycles_mixture: expected an object with a scatter list")
        parts = []
        for k, lobe in enumerate(mix["scatter"]):
            what = "medium.cycles_mixture.scatter[%d]" % k
            parts.append(volume("ShaderNodeVolumeScatter",
                                numbers([lobe.get("density")], 1, what)[0],
                                Color=rgb(lobe.get("color"), what + ".color"),
                                Anisotropy=numbers([lobe.get("anisotropy")], 1,
                                                   what)[0]).outputs[0])
        if "absorption" in mix:
            a = mix["absorption"]
            what = "medium.cycles_mixture.absorption"
            parts.append(volume("ShaderNodeVolumeAbsorption",
                                numbers([a.get("density")], 1, what)[0],
                                Color=rgb(a.get("color"), what + ".color")).outputs[0])
        total = add_all(tree, parts)
        if total is not None:
            tree.links.new(total, out.inputs["Volume"])
        return mat
    v = json_object(item.get("volume"), "medium.volume")
    what = "medium.volume"
    p = volume("ShaderNodeVolumePrincipled",
               numbers([v.get("density")], 1, what + ".density")[0],
               Color=rgb(v.get("color"), what + ".color"),
               Anisotropy=numbers([v.get("anisotropy")], 1, what + ".anisotropy")[0])
    p.inputs["Absorption Color"].default_value = rgb(v.get("absorption_color"),
                                                     what + ".absorption_color")
    tree.links.new(p.outputs[0], out.inputs["Volume"])
    return mat


def atmosphere_setup(item):
    """The medium's "atmosphere" data (scene_export/se_blender_atmo.h)
    checked, or None for a medium in a box."""
    what = "medium.atmosphere"
    a = json_object(item.get("atmosphere"), what, optional=True)
    if a is None:
        return None
    out = {"center": tuple(numbers(a.get("center"), 3, what + ".center"))}
    for k in ("ground_radius", "top_radius", "step_rate", "max_steps"):
        out[k] = numbers([a.get(k)], 1, what + "." + k)[0]
    if not (0 < out["ground_radius"] < out["top_radius"] and out["step_rate"] > 0
            and out["max_steps"] >= 1):
        raise DataError(what + ": expected 0 < ground_radius < top_radius, and step_rate "
                        "and max_steps above 0")
    out["max_steps"] = int(out["max_steps"])
    lists = {}
    for k in ("profiles", "parts", "scatter", "absorption"):
        v = a.get(k)
        if not isinstance(v, list) or not all(isinstance(e, dict) for e in v):
            raise DataError("%s.%s: expected a list of objects" % (what, k))
        lists[k] = v
    out["profiles"] = []
    for i, p in enumerate(lists["profiles"]):
        w = "%s.profiles[%d]" % (what, i)
        if "scale_height" in p:
            h = numbers([p["scale_height"]], 1, w + ".scale_height")[0]
            if not h > 0:
                raise DataError(w + ".scale_height: expected a length above 0")
            out["profiles"].append({"scale_height": h})
        else:
            c = numbers([p.get("center_height")], 1, w + ".center_height")[0]
            hw = numbers([p.get("half_width")], 1, w + ".half_width")[0]
            if not hw > 0:
                raise DataError(w + ".half_width: expected a length above 0")
            out["profiles"].append({"center_height": c, "half_width": hw})

    def index(value, n, w):
        if isinstance(value, bool) or not isinstance(value, int) or not -1 <= value < n:
            raise DataError(w + ": expected an index")
        return value

    np_ = len(out["profiles"])
    out["parts"] = [{"profile": index(p.get("profile"), np_, "%s.parts[%d].profile" % (what, i)),
                     "luminance": numbers([p.get("luminance")], 1,
                                          "%s.parts[%d].luminance" % (what, i))[0]}
                    for i, p in enumerate(lists["parts"])]
    out["scatter"] = []
    for i, s in enumerate(lists["scatter"]):
        w = "%s.scatter[%d]" % (what, i)
        out["scatter"].append({
            "part": index(s.get("part"), len(out["parts"]), w + ".part"),
            "from": numbers([s.get("from")], 1, w + ".from")[0],
            "to": numbers([s.get("to")], 1, w + ".to")[0],
            "anisotropy": numbers([s.get("anisotropy")], 1, w + ".anisotropy")[0],
            "color": rgb(s.get("color"), w + ".color"),
            "density": numbers([s.get("density")], 1, w + ".density")[0]})
    out["absorption"] = []
    for i, s in enumerate(lists["absorption"]):
        w = "%s.absorption[%d]" % (what, i)
        out["absorption"].append({
            "profile": index(s.get("profile"), np_, w + ".profile"),
            "part": index(s.get("part"), len(out["parts"]), w + ".part"),
            "color": rgb(s.get("color"), w + ".color"),
            "density": numbers([s.get("density")], 1, w + ".density")[0]})
    c = a.get("container")
    if not isinstance(c, dict):
        raise DataError(what + ".container: expected a mesh object")
    out["container"] = c
    return out


def atmosphere_material(atmo):
    """The air as a Cycles volume (scene_export/se_blender_atmo.h): the
    densities are node graphs of the distance r to the centre (exp(-h / H)
    at most 1, or the ozone's tent, h = r - R_g, times r < R_t); at each
    shading point one scattering lobe is chosen by White Noise of the
    position, u in [0, 1): part X owns an interval of length q_X = l_X
    rho_X / L (L = sum of l_Y rho_Y), its lobes the slices [from, to) of
    it, and the chosen lobe has density `density` L; Volume Absorption
    closures (colour 1 - a / D, so some channels' coefficients are
    negative) keep the extinction exact whichever lobe is chosen."""
    mat, tree, out = new_material("air")
    set_if(mat.cycles, "homogeneous_volume", False)
    set_if(mat.cycles, "volume_sampling", "MULTIPLE_IMPORTANCE")
    set_if(mat.cycles, "volume_interpolation", "LINEAR")
    # Blender holds the material's rate at >= 1e-3; the scene's rate
    # (setup_render) takes the rest.
    set_if(mat.cycles, "volume_step_rate", max(atmo["step_rate"], 1e-3))
    pos = tree.nodes.new("ShaderNodeNewGeometry").outputs["Position"]
    r = vmath(tree, "DISTANCE", pos, atmo["center"])
    h = smath(tree, "SUBTRACT", r, atmo["ground_radius"])
    inside = smath(tree, "LESS_THAN", r, atmo["top_radius"])
    rho = []
    for p in atmo["profiles"]:
        if "scale_height" in p:
            e = smath(tree, "EXPONENT", smath(tree, "MULTIPLY", h, -1.0 / p["scale_height"]))
            d = smath(tree, "MINIMUM", e, 1.0)
        else:
            off = smath(tree, "ABSOLUTE", smath(tree, "SUBTRACT", h, p["center_height"]))
            d = smath(tree, "MAXIMUM", smath(tree, "SUBTRACT", 1.0, smath(
                tree, "DIVIDE", off, p["half_width"])), 0.0)
        rho.append(smath(tree, "MULTIPLY", d, inside))
    noise = tree.nodes.new("ShaderNodeTexWhiteNoise")
    noise.noise_dimensions = "3D"
    tree.links.new(pos, noise.inputs["Vector"])
    u = noise.outputs["Value"]
    total = None
    shares = []
    for p in atmo["parts"]:
        s = smath(tree, "MULTIPLY", rho[p["profile"]], p["luminance"])
        shares.append(s)
        total = s if total is None else smath(tree, "ADD", total, s)
    # Each part's interval [start, start + q) of u; the last one's end is
    # 2, so that rounding leaves no gap below 1.
    starts, lengths, start = [], [], 0.0
    for k, s in enumerate(shares):
        q = smath(tree, "DIVIDE", s, total)
        starts.append(start)
        lengths.append(q)
        start = smath(tree, "ADD", start, q)
    last = len(shares) - 1

    def chosen(part, a, b):
        """1 where start + a q <= u < start + b q for the part, else 0."""
        lo = smath(tree, "ADD", starts[part], smath(tree, "MULTIPLY", lengths[part], a))
        hi = (2.0 if part == last and b >= 1.0 else
              smath(tree, "ADD", starts[part], smath(tree, "MULTIPLY", lengths[part], b)))
        below_hi = 1.0 if hi == 2.0 else smath(tree, "LESS_THAN", u, hi)
        return smath(tree, "SUBTRACT", below_hi, smath(tree, "LESS_THAN", u, lo))

    parts = []
    for s in atmo["scatter"]:
        n = node(tree, "ShaderNodeVolumeScatter", Color=s["color"], Anisotropy=s["anisotropy"])
        d = smath(tree, "MULTIPLY", smath(tree, "MULTIPLY", total, s["density"]),
                  chosen(s["part"], s["from"], s["to"]))
        tree.links.new(d, n.inputs["Density"])
        parts.append(n.outputs[0])
    for s in atmo["absorption"]:
        n = node(tree, "ShaderNodeVolumeAbsorption", Color=s["color"])
        d = smath(tree, "MULTIPLY", rho[s["profile"]], s["density"])
        if s["part"] >= 0:
            d = smath(tree, "MULTIPLY", d, chosen(s["part"], 0.0, 1.0))
        tree.links.new(d, n.inputs["Density"])
        parts.append(n.outputs[0])
    volume = add_all(tree, parts)
    if volume is not None:
        tree.links.new(volume, out.inputs["Volume"])
    return mat


# The add-on's medium properties (material.shafts_medium, the add-on's
# properties.ShaftsMediumSettings) as raw ID properties, which the add-on
# reads when it is installed and Blender keeps when it is not: the kind and
# phase enums by number, every length and coefficient in the scene's own
# units and frame, in double precision (the add-on maps them through the
# collection's frame, shafts_scale, shafts_origin and shafts_axes).
MEDIUM_KINDS = {"height_fog": 1, "atmosphere": 2}
MEDIUM_PHASES = ("isotropic", "henyey_greenstein", "nishita_hazy", "nishita_murky",
                 "rayleigh", "cornette_shanks")


def _phase_number(phase, what):
    if not isinstance(phase, dict) or phase.get("type") not in MEDIUM_PHASES:
        raise DataError(what + ": expected a phase object of the scene format")
    g = numbers([phase.get("g", 0.0)], 1, what + ".g")[0]
    return MEDIUM_PHASES.index(phase["type"]), g


def medium_properties(item):
    """The raw properties for the scene's medium (data medium.scene, the
    scene format's medium object), or None for a homogeneous one (the node
    graph is exact for it)."""
    what = "medium.scene"
    m = json_object(item.get("scene"), what, optional=True)
    if m is None:
        return None
    kind = MEDIUM_KINDS.get(m.get("type"))
    if kind is None:
        return None
    if kind == 1:
        phase, g = _phase_number(m.get("phase"), what + ".phase")
        return {"kind": 1, "sigma_s": numbers(m.get("sigma_s"), 3, what + ".sigma_s"),
                "sigma_a": numbers(m.get("sigma_a"), 3, what + ".sigma_a"),
                "base_height": numbers([m.get("base_height")], 1, what + ".base_height")[0],
                "scale_height": numbers([m.get("scale_height")], 1, what + ".scale_height")[0],
                "phase": phase, "phase_g": g}
    r = json_object(m.get("rayleigh"), what + ".rayleigh")
    p = {"kind": 2, "center": numbers(m.get("center"), 3, what + ".center"),
         "ground_radius": numbers([m.get("ground_radius")], 1, what + ".ground_radius")[0],
         "top_radius": numbers([m.get("top_radius")], 1, what + ".top_radius")[0],
         "ground_albedo": numbers(m.get("ground_albedo"), 3, what + ".ground_albedo"),
         "rayleigh_sigma_s": numbers(r.get("sigma_s"), 3, what + ".rayleigh.sigma_s"),
         "rayleigh_scale_height": numbers([r.get("scale_height")], 1,
                                          what + ".rayleigh.scale_height")[0],
         "use_mie": "mie" in m, "use_ozone": "ozone" in m}
    if "mie" in m:
        mie = json_object(m["mie"], what + ".mie")
        p["mie_phase"], p["mie_g"] = _phase_number(mie.get("phase"), what + ".mie.phase")
        p["mie_sigma_s"] = numbers(mie.get("sigma_s"), 3, what + ".mie.sigma_s")
        p["mie_sigma_a"] = numbers(mie.get("sigma_a", [0.0] * 3), 3, what + ".mie.sigma_a")
        p["mie_scale_height"] = numbers([mie.get("scale_height")], 1,
                                        what + ".mie.scale_height")[0]
    if "ozone" in m:
        o = json_object(m["ozone"], what + ".ozone")
        p["ozone_sigma_a"] = numbers(o.get("sigma_a"), 3, what + ".ozone.sigma_a")
        p["ozone_center_height"] = numbers([o.get("center_height")], 1,
                                           what + ".ozone.center_height")[0]
        p["ozone_width"] = numbers([o.get("width")], 1, what + ".ozone.width")[0]
    return p


def phase_record(item, engine):
    """For a homogeneous medium, the scene's own phase and the g of the
    lobes the material holds for `engine` (raw property shafts_phase), or
    None without the scene's medium (data medium.scene). Cycles has no
    Nishita, Rayleigh or Cornette-Shanks phase; the add-on's converter
    (convert/medium.py) gives our engines this exact phase back as long as
    the node graph still holds these lobes."""
    m = json_object(item.get("scene"), "medium.scene", optional=True)
    if m is None:
        return None
    phase, g = _phase_number(m.get("phase"), "medium.scene.phase")
    mix = item.get("cycles_mixture")
    if engine == "cycles" and isinstance(mix, dict) and isinstance(mix.get("scatter"), list):
        lobes = [numbers([json_object(lobe, "medium.cycles_mixture.scatter[%d]" % k)
                          .get("anisotropy")], 1, "medium.cycles_mixture.scatter")[0]
                 for k, lobe in enumerate(mix["scatter"])]
    else:
        v = json_object(item.get("volume"), "medium.volume")
        lobes = numbers([v.get("anisotropy")], 1, "medium.volume.anisotropy")
    return {"phase": phase, "phase_g": g, "lobes": lobes}


def set_frame_properties(collection, data):
    """The writer's frame on the collection (shafts_scale, shafts_origin,
    shafts_axes: a scene point p is at (p - origin) scale along the named
    axes), which the add-on maps the medium's properties through."""
    frame = json_object(data.get("frame", {}), "frame")
    axes = frame.get("axes", ["+x", "-z", "+y"])
    if (not isinstance(axes, list) or len(axes) != 3
            or not all(a in ("+x", "-x", "+y", "-y", "+z", "-z") for a in axes)):
        raise DataError("frame.axes: expected three signed axis names")
    collection["shafts_scale"] = numbers([frame.get("scale", 1.0)], 1, "frame.scale")[0]
    collection["shafts_origin"] = numbers(frame.get("origin", [0.0, 0.0, 0.0]), 3,
                                          "frame.origin")
    collection["shafts_axes"] = " ".join(axes)


def box_mesh(lo, hi):
    v = [(lo[0] if i & 1 == 0 else hi[0], lo[1] if i & 2 == 0 else hi[1],
          lo[2] if i & 4 == 0 else hi[2]) for i in range(8)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    mesh = bpy.data.meshes.new("medium box")
    mesh.from_pydata(v, [], faces)
    mesh.update()
    return mesh


def image_size(r, opts):
    """The image size: the data's render size, or --width/--height with the
    other side following the data's aspect (as sh_cli_resize does; the
    camera keeps its vertical field of view)."""
    w, h = int(r.get("width", 64)), int(r.get("height", 48))
    ow, oh = opts.get("width"), opts.get("height")
    if ow and not oh:
        oh = max(1, int(math.floor(ow * h / w + 0.5)))
    elif oh and not ow:
        ow = max(1, int(math.floor(oh * w / h + 0.5)))
    return (ow, oh) if ow else (w, h)


def setup_render(scene, data, opts, medium_box):
    r = data.get("render", {})
    render = scene.render
    render.resolution_x, render.resolution_y = image_size(r, opts)
    render.resolution_percentage = 100
    render.pixel_aspect_x = render.pixel_aspect_y = 1.0
    render.dither_intensity = 0.0
    render.film_transparent = False
    render.use_compositing = False
    render.use_sequencer = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.color_mode = "RGB"
    settings.exr_codec = "ZIP"
    depth = int(r.get("max_depth", 5))
    if opts["engine"] == "cycles":
        render.engine = "CYCLES"
        c = scene.cycles
        c.device = "CPU"
        c.samples = opts["samples"] or int(r.get("samples_cycles", 64))
        c.seed = opts["seed"] if opts["seed"] is not None else int(r.get("seed", 0))
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.max_bounces = depth
        c.diffuse_bounces = 0
        c.glossy_bounces = depth
        c.transmission_bounces = depth
        c.volume_bounces = 0
        fog = fog_setup(data["medium"]) if "medium" in data else None
        if fog is not None:
            c.volume_max_steps = max(int(c.volume_max_steps), fog["max_steps"])
        atmo = atmosphere_setup(data["medium"]) if "medium" in data else None
        if atmo is not None:
            c.volume_max_steps = max(int(c.volume_max_steps), atmo["max_steps"])
            # What the material's rate (at least 1e-3) leaves to the scene's.
            c.volume_step_rate = min(1.0, max(0.01, atmo["step_rate"] / 1e-3))
        c.transparent_max_bounces = 64
        c.caustics_reflective = False
        c.caustics_refractive = False
        c.blur_glossy = 0.0
        c.sample_clamp_direct = 0.0
        c.sample_clamp_indirect = 0.0
        c.light_sampling_threshold = 0.0
        c.pixel_filter_type = "GAUSSIAN"
        c.filter_width = 0.01
        c.film_exposure = 1.0
        if hasattr(c, "use_guiding"):
            c.use_guiding = False
    else:
        render.engine = "BLENDER_EEVEE"
        e = scene.eevee
        e.taa_render_samples = opts["samples"] or int(r.get("samples_eevee", 16))
        render.filter_size = 0.01
        e.use_gtao = False
        e.use_bloom = False
        e.use_ssr = True
        e.use_ssr_refraction = True
        e.use_soft_shadows = False
        e.use_shadow_high_bitdepth = True
        e.shadow_cube_size = "2048"
        e.shadow_cascade_size = "2048"
        e.light_threshold = 1e-4
        e.use_volumetric_lights = True
        e.use_volumetric_shadows = True
        e.volumetric_samples = 256
        e.volumetric_shadow_samples = 32
        e.volumetric_tile_size = "2"
        e.volumetric_sample_distribution = 0.8
        e.volumetric_light_clamp = 0.0
        cam = scene.camera
        e.volumetric_start = max(cam.data.clip_start, 1e-3)
        far = cam.data.clip_start * 10
        if medium_box is not None:
            lo, hi = medium_box
            p = cam.matrix_world.translation
            for i in range(8):
                corner = (lo[0] if i & 1 == 0 else hi[0], lo[1] if i & 2 == 0 else hi[1],
                          lo[2] if i & 4 == 0 else hi[2])
                far = max(far, math.dist(p, corner))
        e.volumetric_end = far * 1.01


def check_format(data):
    if not isinstance(data, dict) or data.get("format") != "shafts-blender" or data.get("version") != 1:
        raise DataError("not a scene_export Blender data file (format shafts-blender, version 1)")


def shadow_clip_start(position, cards):
    """Where EEVEE's shadow maps of a point or spot light at `position`
    begin: Blender's default, 0.05 m, or a quarter of the distance to the
    nearest vertex of the cards this engine gets when that is nearer. A spot's card lies 2e-3 of the
    scene's radius in front of the light, and a card nearer than the start
    casts nothing, light map included. (Five times the camera's clip start
    was used before; the clip start now lies just before the scene's
    content, 1.14 units on lmm_table, so the maps began past the table and
    its point light cast no shadow: EEVEE 22% off instead of 0.69%.)"""
    nearest = 0.2
    for k, card in enumerate(cards):
        v = numbers(card.get("vertices"), None, "cards[%d].vertices" % k)
        for i in range(0, len(v) - 2, 3):
            d = ((v[i] - position[0]) ** 2 + (v[i + 1] - position[1]) ** 2
                 + (v[i + 2] - position[2]) ** 2) ** 0.5
            nearest = min(nearest, d)
    return 0.25 * nearest


def build(data, base_dir, opts):
    """The script's scene: factory settings, the data's objects and the
    render settings for opts["engine"]."""
    check_format(data)
    for line in data.get("notes", []):
        print("scene_export note: %s" % str(line).replace("\n", " "))
    if opts["engine"] == "eevee":
        for line in data.get("eevee_notes", []):
            print("scene_export note (EEVEE): %s" % str(line).replace("\n", " "))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    medium_box = build_into(scene, scene.collection, data, base_dir, opts["engine"])
    setup_render(scene, data, opts, medium_box)
    return scene


def build_into(scene, collection, data, base_dir, engine):
    """Adds the data's world, camera (made the scene's camera), lights,
    meshes, cards and medium to `collection`, with the materials for
    `engine` ("cycles" or "eevee"); returns the medium's box (lo, hi) or
    None. Raises DataError for data the exporter does not write."""
    check_format(data)
    atmo = atmosphere_setup(data["medium"]) if isinstance(data.get("medium"), dict) else None
    if atmo is not None and engine == "eevee":
        raise DataError("medium.atmosphere: EEVEE does not render a planet's atmosphere "
                        "(its froxel grid spans the view frustum, far too coarse for air "
                        "kilometres thick seen from a metre above the ground, and it has no "
                        "per-point phase mixture); render it with --engine cycles")

    # World: the background radiance, seen by camera, mirror and refracted
    # rays but lighting nothing (diffuse and volume rays see black), never
    # sampled as a light.
    world = bpy.data.worlds.new("background")
    scene.world = world
    world.use_nodes = True
    wt = world.node_tree
    wt.nodes.clear()
    wout = wt.nodes.new("ShaderNodeOutputWorld")
    bg = node(wt, "ShaderNodeBackground",
              Color=rgb(data.get("world", {}).get("background"), "world.background"), Strength=1.0)
    disks = sun_disks(wt, data.get("world", {}))
    if disks:
        wt.links.new(disks, bg.inputs["Color"])
    black = node(wt, "ShaderNodeBackground", Color=(0, 0, 0, 1), Strength=0.0)
    wmix = wt.nodes.new("ShaderNodeMixShader")
    wt.links.new(seen_by_traced_rays(wt), wmix.inputs["Fac"])
    wt.links.new(black.outputs[0], wmix.inputs[1])
    wt.links.new(bg.outputs[0], wmix.inputs[2])
    wt.links.new(wmix.outputs[0], wout.inputs["Surface"])
    world.cycles.sampling_method = "NONE"

    cam_item = data.get("camera", {})
    cam = bpy.data.cameras.new("camera")
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = numbers([cam_item.get("fov_y")], 1, "camera.fov_y")[0]
    cam.clip_start = numbers([cam_item.get("clip_start")], 1, "camera.clip_start")[0]
    cam.clip_end = numbers([cam_item.get("clip_end")], 1, "camera.clip_end")[0]
    cam_obj = new_object("camera", cam, collection)
    cam_obj.matrix_world = matrix(cam_item.get("matrix"), "camera.matrix")
    scene.camera = cam_obj

    for k, item in enumerate(data.get("lights", [])):
        what = "lights[%d]" % k
        kind = item.get("type")
        if kind not in ("POINT", "SPOT", "SUN"):
            raise DataError(what + ".type: expected POINT, SPOT or SUN")
        light = bpy.data.lights.new("light%d" % k, kind)
        light.color = rgb(item.get("color"), what + ".color")[:3]
        # A spot whose exponent Cycles needs a card for has Cycles' power
        # times the card's factor; EEVEE gets the plain power (no card).
        energy = "eevee_energy" if engine == "eevee" and "eevee_energy" in item else "energy"
        light.energy = numbers([item.get(energy)], 1, what + "." + energy)[0]
        light.use_shadow = True
        set_if(light, "use_contact_shadow", False)
        set_if(getattr(light, "cycles", None), "cast_shadow", True)
        if kind == "SUN":
            light.angle = 0.0
        else:
            light.shadow_soft_size = 0.0
            set_if(light, "shadow_buffer_clip_start", shadow_clip_start(
                matrix(item.get("matrix"), what + ".matrix").translation,
                [c for c in data.get("cards", []) if c.get("engine", engine) == engine]))
        if kind == "SPOT":
            light.spot_size = numbers([item.get("spot_size")], 1, what + ".spot_size")[0]
            light.spot_blend = numbers([item.get("spot_blend")], 1, what + ".spot_blend")[0]
        obj = new_object("light%d" % k, light, collection)
        obj.matrix_world = matrix(item.get("matrix"), what + ".matrix")

    # Light maps: plain file names next to the data file. Blender reads a
    # backslash in an image path as a directory separator, so each image is
    # copied to a fresh temporary directory, loaded from there and packed.
    images = []
    staging = tempfile.mkdtemp(prefix="scene_export_")
    try:
        for k, item in enumerate(data.get("images", [])):
            name = item.get("file")
            if not isinstance(name, str) or os.path.basename(name) != name or name in ("", ".", ".."):
                raise DataError("images[%d].file: expected a file name in the data file's directory" % k)
            copy = os.path.join(staging, "map%d.exr" % k)
            try:
                shutil.copyfile(os.path.join(base_dir, name), copy)
            except OSError as e:
                raise DataError("images[%d]: cannot read %s: %s" % (k, name, e))
            img = bpy.data.images.load(copy, check_existing=False)
            img.colorspace_settings.name = "Non-Color"
            img.pack()
            images.append(img)
    finally:
        shutil.rmtree(staging, ignore_errors=True)

    transmittance = transmittance_setup(data, engine)
    materials = [surface_material(item, k, transmittance)
                 for k, item in enumerate(data.get("materials", []))]
    for k, item in enumerate(data.get("meshes", [])):
        what = "meshes[%d]" % k
        mi = item.get("material")
        if isinstance(mi, bool) or not isinstance(mi, int) or not 0 <= mi < len(materials):
            raise DataError(what + ".material: expected a material index")
        mesh = build_mesh("shape%d" % k, item, what)
        if item.get("smooth"):
            for poly in mesh.polygons:
                poly.use_smooth = True
            set_if(mesh, "use_auto_smooth", True)
            set_if(mesh, "auto_smooth_angle", math.radians(50.0))
        mesh.materials.append(materials[mi])
        obj = new_object("shape%d %s" % (k, str(item.get("label", ""))[:20]), mesh, collection)
        if item.get("atmosphere_ground"):
            # The add-on's import takes the atmosphere's exact ground sphere
            # instead of this tessellation (convert/scene.py).
            obj["shafts_atmosphere_ground"] = True

    for k, item in enumerate(data.get("cards", [])):
        what = "cards[%d]" % k
        if item.get("engine", engine) != engine:
            continue  # another engine's card (a Cycles spot profile, say)
        mesh = build_mesh("card%d" % k, item, what)
        if "uvs" in item:
            uvs = numbers(item["uvs"], 2 * len(mesh.vertices), what + ".uvs")
            layer = mesh.uv_layers.new(name="UVMap")
            for loop in mesh.loops:
                layer.data[loop.index].uv = (uvs[2 * loop.vertex_index], uvs[2 * loop.vertex_index + 1])
        mesh.materials.append(card_material(item, images, k))
        obj = new_object("card%d" % k, mesh, collection)
        obj.visible_camera = False
        obj.visible_diffuse = False
        obj.visible_glossy = False
        obj.visible_transmission = False
        obj.visible_volume_scatter = False
        obj.visible_shadow = True

    medium_box = None
    set_frame_properties(collection, data)
    if "medium" in data:
        item = data["medium"]
        lo = numbers(item.get("min"), 3, "medium.min")
        hi = numbers(item.get("max"), 3, "medium.max")
        if atmo is not None:
            mesh = build_mesh("air", atmo["container"], "medium.atmosphere.container")
            mesh.materials.append(atmosphere_material(atmo))
        else:
            mesh = box_mesh(lo, hi)
            mesh.materials.append(volume_material(item, engine))
        props = medium_properties(item)
        if props is not None:
            mesh.materials[0]["shafts_medium"] = props
        elif atmo is None:
            written = phase_record(item, engine)
            if written is not None:
                mesh.materials[0]["shafts_phase"] = written
        new_object("medium", mesh, collection)
        medium_box = (lo, hi)
    return medium_box


# Cycles 3.4's ray marching (intern/cycles/kernel/integrator/shade_volume.h,
# volume_integrate_heterogeneous) picks the colour channel it samples a
# scattering distance in at every step from the same random number
# (vstate.rphase, drawn once per path), while the channels' probabilities
# follow the path's throughput; the paths that get through a step are then
# those whose number picks the channel with the least extinction, and they
# keep picking it, so a medium whose extinction differs between channels
# scatters too little (docs/scene_export.md, "The atmosphere in Cycles").
# With grey coefficients every channel sees the same extinction and the
# estimate is exact, so such a scene is rendered once per channel.
CHANNEL_NAMES = ("red", "green", "blue")


def chromatic_marched_inputs(scene):
    """The unlinked colour inputs of the ray-marched (not homogeneous)
    volume materials of the scene's objects, as (socket, original value)
    pairs, when one of them differs between its R, G and B; otherwise []
    (grey or homogeneous media render exactly in one pass)."""
    inputs, chromatic, seen = [], False, set()
    for obj in scene.objects:
        for slot in getattr(obj, "material_slots", []):
            mat = slot.material
            if mat is None or mat.name in seen or not mat.use_nodes or mat.node_tree is None:
                continue
            seen.add(mat.name)
            if getattr(mat.cycles, "homogeneous_volume", True):
                continue
            tree = mat.node_tree
            if not any(n.type == "OUTPUT_MATERIAL" and n.inputs["Volume"].is_linked
                       for n in tree.nodes):
                continue
            for n in tree.nodes:
                for sock in n.inputs:
                    if sock.type == "RGBA" and not sock.is_linked:
                        v = tuple(sock.default_value)
                        inputs.append((sock, v))
                        chromatic = chromatic or v[0] != v[1] or v[1] != v[2]
    return inputs if chromatic else []


def set_channel(inputs, c):
    """Every input of chromatic_marched_inputs set to its channel c in R,
    G and B (its alpha kept); c None restores the original values."""
    for sock, v in inputs:
        sock.default_value = v if c is None else (v[c], v[c], v[c], v[3])


def render_still(scene, path):
    """Renders the scene's frame into the image file `path`."""
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    if not os.path.exists(path):
        raise RuntimeError("Blender wrote no image")
    return path


def compose_channels(passes, path, scene):
    """Writes to `path`, in the scene's output format, the image whose
    channel c is channel c of the image file passes[c] (c = 0, 1, 2), its
    alpha the first pass's. The files are read and written as linear data
    (no colour conversion). Raises RuntimeError if they differ in size."""
    images = [bpy.data.images.load(p, check_existing=False) for p in passes]
    composed = None
    try:
        for im in images:
            im.colorspace_settings.name = "Non-Color"
        w, h = images[0].size
        stride = images[0].channels
        if any(tuple(im.size) != (w, h) or im.channels != stride for im in images) or stride < 3:
            raise RuntimeError("the channel passes differ in size or have fewer than 3 channels")
        out = array.array("f", bytes(4 * stride * w * h))
        images[0].pixels.foreach_get(out)
        buf = array.array("f", bytes(4 * stride * w * h))
        for c in (1, 2):
            images[c].pixels.foreach_get(buf)
            out[c::stride] = buf[c::stride]
        composed = bpy.data.images.new("composed", w, h, alpha=stride == 4, float_buffer=True)
        composed.colorspace_settings.name = "Non-Color"
        composed.pixels.foreach_set(out)
        composed.save_render(path, scene=scene)
    finally:
        for im in images + ([composed] if composed is not None else []):
            bpy.data.images.remove(im)
    if not os.path.exists(path):
        raise RuntimeError("Blender wrote no composed image")
    return path


def render_image(scene, opts, staging):
    """The scene rendered into a file in `staging` (its path): one render,
    or, for Cycles with a chromatic ray-marched medium and without
    --one-pass, one per channel with grey coefficients, composed. Says which
    on stdout."""
    inputs = (chromatic_marched_inputs(scene)
              if opts["engine"] == "cycles" and not opts["one_pass"] else [])
    if not inputs:
        return render_still(scene, os.path.join(staging, "render.exr"))
    print("scene_export script: a ray-marched medium's coefficients differ between "
          "colour channels, which Cycles 3.4 renders too dark: rendering one pass per "
          "channel with grey coefficients (channel c of pass c; --one-pass renders once)")
    passes = []
    try:
        for c, name in enumerate(CHANNEL_NAMES):
            print("scene_export script: pass %d of 3: the %s channel's coefficients"
                  % (c + 1, name), flush=True)
            set_channel(inputs, c)
            passes.append(render_still(scene, os.path.join(staging, "pass_%s.exr" % name)))
    finally:
        set_channel(inputs, None)
    return compose_channels(passes, os.path.join(staging, "render.exr"), scene)


def main():
    try:
        opts = parse_args(sys.argv)
        data_path = os.path.splitext(os.path.abspath(__file__))[0] + ".blender.json"
        try:
            with open(data_path, "r", encoding="utf-8") as f:
                data = json.load(f)
        except (OSError, ValueError) as e:
            raise DataError("cannot read the scene data %s: %s" % (data_path, e))
        scene = build(data, os.path.dirname(data_path), opts)
    except DataError as e:
        print("scene_export script: error: %s" % e, file=sys.stderr)
        sys.exit(2)
    except Exception as e:  # Blender refused the data: report, never go on
        print("scene_export script: error: cannot build the scene: %s: %s"
              % (type(e).__name__, e), file=sys.stderr)
        sys.exit(1)
    # Blender reads a backslash in an output path as a directory separator:
    # render into a fresh temporary directory, then copy the image next to
    # its destination and rename it into place.
    out = opts["out"]
    staging = tempfile.mkdtemp(prefix="scene_export_")
    tmp = os.path.join(os.path.dirname(out), ".%s.tmp%d" % (os.path.basename(out), os.getpid()))
    try:
        rendered = render_image(scene, opts, staging)
        shutil.copyfile(rendered, tmp)
        os.replace(tmp, out)
    except Exception as e:  # rendering or writing failed: leave nothing behind
        if os.path.exists(tmp):
            os.unlink(tmp)
        print("scene_export script: error: rendering failed: %s" % e, file=sys.stderr)
        sys.exit(1)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    print("scene_export script: wrote %s" % out)


if __name__ == "__main__":
    main()
