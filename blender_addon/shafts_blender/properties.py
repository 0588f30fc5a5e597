"""The add-on's settings, stored in the .blend file.

Render settings of each engine live on the scene (``scene.shafts_sweep``,
``scene.shafts_tracer``); the light meshes method's soft-shadow controls on
each light (``light.shafts``) and material (``material.shafts``), where the
converter reads them into the scene's ``soft_shadows``,
``casts_soft_shadows`` and ``receives_soft_shadows`` keys
(docs/scene-format.md); the kind of medium a volume material stands for
(``material.shafts_medium``: the node graph's homogeneous medium, height fog
or a planet's atmosphere, with their parameters) is read by convert/medium.py.
The engines turn the render settings into the
arguments of shafts.py (``sweep_options``, ``tracer_arguments``), so a value
reaches the library in one place only.
"""
import bpy
from bpy.props import (BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty,
                       IntProperty, PointerProperty)


class ShaftsSweepSettings(bpy.types.PropertyGroup):
    """gl_shafts' options (gl_shafts/gs_render.h: gs_options); 0 means the
    built-in default for the light's kind where the header says so."""
    planes: IntProperty(
        name="Planes", default=0, min=0, max=100000,
        description="Virtual planes swept per light; 0: by the light's kind "
                    "(4 for point and spot lights, 8 for directional ones)")
    lattice: IntProperty(
        name="Lattice", default=20, min=2, max=4096,
        description="Lattice points per plane side on which the scattering term is evaluated")
    shadow_map_res: IntProperty(
        name="Shadow Map", default=0, min=0, max=16384, subtype='PIXEL',
        description="Shadow-map size in texels; 0: by the light's kind "
                    "(1024 for point and spot lights, 2048 for directional ones)")
    light_map_res: IntProperty(
        name="Light Map", default=0, min=0, max=16384, subtype='PIXEL',
        description="Light maps (gobos, windows) resampled to this size; 0: their own size")
    sub_angle_deg: FloatProperty(
        name="Sub-Angle", default=4.0, min=0.01, max=30.0,
        description="Point and spot lights: one sample per this angle (degrees) that a "
                    "plane's part of a ray subtends at the light")
    sub_texels: FloatProperty(
        name="Sub-Texels", default=2.0, min=0.01, max=1000.0,
        description="Lights with a map: one sample per this many texels of the map "
                    "that a plane's part of a ray crosses")
    xi: EnumProperty(
        name="Scattering Term",
        items=(('EXACT', "Exact", "Evaluate the scattering term per fragment"),
               ('LATTICE', "Lattice", "Interpolate it from the lattice (the paper's method)")),
        default='EXACT')
    jitter: BoolProperty(
        name="Jitter", default=False,
        description="Jitter the planes' sample depths per pixel (noise instead of banding)")
    viewport_divider: IntProperty(
        name="Viewport Divider", default=1, min=1, max=8,
        description="The viewport renders at 1/N of its size, drawn scaled up")


class ShaftsTracerSettings(bpy.types.PropertyGroup):
    """lmm_tracer's options (lmm_tracer/main.c, docs/lmm.md)."""
    mode: EnumProperty(
        name="Mode",
        items=(('REFERENCE', "Reference", "The converged reference renderer (ground truth)"),
               ('WHITTED', "Whitted", "Whitted ray tracing with single scattering"),
               ('LMM', "Light Meshes", "Soft shadows by the light meshes method")),
        default='REFERENCE')
    scheme: EnumProperty(
        name="Scheme",
        items=(('DEFAULT', "Default", "The mode's default (refract-trace)"),
               ('STRAIGHT', "Straight", "No refraction"),
               ('REFRACT_TRACE', "Refract-Trace", "Refraction followed by tracing"),
               ('REFRACT_BOTH', "Refract-Both", "Refraction followed for light meshes too "
                                                "(light meshes mode only)")),
        default='DEFAULT')
    refined: BoolProperty(
        name="Refined", default=False,
        description="Light meshes with Scheme Refract-Both: the refined variant "
                    "(refused under any other scheme)")
    mesh_step: FloatProperty(
        name="Mesh Step", default=0.0, min=0.0, subtype='DISTANCE',
        description="Light meshes: mesh step H; 0: 1/100 of the shapes' diagonal")
    radius: FloatProperty(
        name="Radius Factor", default=2.0, min=0.01, max=100.0,
        description="Light meshes: interpolation radius r = H times this factor")
    volume: EnumProperty(
        name="Volume Shadows",
        items=(('MESH', "Mesh", "Interpolate volumetric shadows from the light mesh"),
               ('EXACT', "Exact", "Trace volumetric shadows")),
        default='MESH')
    spp: IntProperty(
        name="Samples", default=16, min=1, max=1000000,
        description="In-scattering samples per ray segment and light")
    max_depth: IntProperty(
        name="Max Depth", default=5, min=0, max=64,
        description="Reflection and refraction depth")
    seed: IntProperty(name="Seed", default=0, min=0, description="Random seed")
    threads: IntProperty(
        name="Threads", default=0, min=0, max=1024,
        description="Worker threads; 0: one per CPU")
    viewport_spp: IntProperty(
        name="Viewport Samples", default=4, min=1, max=1000000,
        description="Viewport: the most samples progressive refinement goes up to")
    viewport_divider: IntProperty(
        name="Viewport Divider", default=2, min=1, max=8,
        description="The viewport renders at 1/N of its size, drawn scaled up")


def _tag(settings, context):
    """Tags the light or material for the depsgraph: the converter reads the
    evaluated copy, which Blender would not refresh for a change of these
    settings alone (measured: an export after the change still had the old
    value)."""
    settings.id_data.update_tag()


class ShaftsLightSettings(bpy.types.PropertyGroup):
    soft_shadows: BoolProperty(
        name="Soft Shadows", default=True, update=_tag,
        description="Light meshes mode: this light's shadows are softened")


class ShaftsMaterialSettings(bpy.types.PropertyGroup):
    casts_soft_shadows: BoolProperty(
        name="Casts Soft Shadows", default=True, update=_tag,
        description="Light meshes mode: the shadow this surface casts is softened")
    receives_soft_shadows: BoolProperty(
        name="Receives Soft Shadows", default=True, update=_tag,
        description="Light meshes mode: shadows falling on this surface are softened")


# The scene format's phase functions (docs/scene-format.md), numbered as
# scene_export's Blender writer stores them (blender_build.MEDIUM_PHASES).
PHASES = (('ISOTROPIC', "Isotropic", "", 0),
          ('HENYEY_GREENSTEIN', "Henyey-Greenstein", "g from the Anisotropy below", 1),
          ('NISHITA_HAZY', "Nishita Hazy", "Nishita et al. 1993: hazy air", 2),
          ('NISHITA_MURKY', "Nishita Murky", "Nishita et al. 1993: murky air", 3),
          ('RAYLEIGH', "Rayleigh", "", 4),
          ('CORNETTE_SHANKS', "Cornette-Shanks", "g from the Anisotropy below", 5))


def _rgb(name, default, description):
    return FloatVectorProperty(name=name, size=3, default=default, min=0.0, precision=6,
                               update=_tag, description=description)


def _length(name, default, description, minimum=None):
    kw = {} if minimum is None else {"min": minimum}
    return FloatProperty(name=name, default=default, precision=4, update=_tag,
                         description=description, **kw)


class ShaftsMediumSettings(bpy.types.PropertyGroup):
    """The medium a volume material stands for in our engines
    (docs/scene-format.md, "Non-uniform media"; docs/blender.md). Lengths
    and coefficients are in the scene's units: Blender's, unless the
    object's collection holds scene_export's frame (shafts_scale,
    shafts_origin, shafts_axes), which then maps them; points and heights
    are in the scene's frame, Y up (Blender's Z). The defaults are the
    Earth's values the scene format gives (per kilometre)."""
    kind: EnumProperty(
        name="Medium", update=_tag, default='NODES',
        items=(('NODES', "Homogeneous", "The node graph's homogeneous medium in the "
                "object's box (a linked Density is approximated)", 0),
               ('HEIGHT_FOG', "Height Fog", "Density falling exponentially with height "
                "in the object's box; coefficients, heights and phase below", 1),
               ('ATMOSPHERE', "Atmosphere", "A planet's air: Rayleigh and Mie scattering "
                "and ozone between two spheres, the ground an opaque sphere", 2)))
    sigma_s: _rgb("Scattering", (0.05, 0.05, 0.05),
                  "Height fog: sigma_s at the base height, per scene unit")
    sigma_a: _rgb("Absorption", (0.0, 0.0, 0.0),
                  "Height fog: sigma_a at the base height, per scene unit")
    base_height: _length("Base Height", 0.0,
                         "Height fog: the height (scene Y, Blender Z) of the base level")
    scale_height: _length("Scale Height", 1.0, "Height fog: H, the coefficients are "
                          "their base values times exp(-(y - base) / H)", 1e-9)
    phase: EnumProperty(name="Phase", items=PHASES, default='ISOTROPIC', update=_tag)
    phase_g: FloatProperty(name="Anisotropy", default=0.0, min=-0.999, max=0.999,
                           update=_tag, description="g of the phase function")
    center: FloatVectorProperty(
        name="Centre", size=3, default=(0.0, -6360.0, 0.0), precision=4, update=_tag,
        description="Atmosphere: the planet's centre in the scene's frame (Y up)")
    ground_radius: _length("Ground Radius", 6360.0, "Atmosphere: R_g, the opaque ground "
                           "sphere", 1e-9)
    top_radius: _length("Top Radius", 6420.0, "Atmosphere: R_t, vacuum above", 1e-9)
    ground_albedo: _rgb("Ground Albedo", (0.1, 0.1, 0.1), "Atmosphere: the ground's "
                        "Lambert albedo")
    rayleigh_sigma_s: _rgb("Rayleigh Scattering", (5.802e-3, 13.558e-3, 33.1e-3),
                           "Atmosphere: Rayleigh sigma_s at the ground, per scene unit")
    rayleigh_scale_height: _length("Rayleigh Scale Height", 8.0, "Atmosphere: H_R", 1e-9)
    use_mie: BoolProperty(name="Mie", default=True, update=_tag,
                          description="Atmosphere: aerosols (Mie scattering)")
    mie_sigma_s: _rgb("Mie Scattering", (3.996e-3,) * 3,
                      "Atmosphere: Mie sigma_s at the ground, per scene unit")
    mie_sigma_a: _rgb("Mie Absorption", (0.444e-3,) * 3,
                      "Atmosphere: Mie sigma_a at the ground, per scene unit")
    mie_scale_height: _length("Mie Scale Height", 1.2, "Atmosphere: H_M", 1e-9)
    mie_phase: EnumProperty(name="Mie Phase", items=PHASES, default='CORNETTE_SHANKS',
                            update=_tag)
    mie_g: FloatProperty(name="Mie g", default=0.8, min=-0.999, max=0.999, update=_tag,
                         description="Atmosphere: g of the Mie phase function")
    use_ozone: BoolProperty(name="Ozone", default=True, update=_tag,
                            description="Atmosphere: an absorbing ozone layer")
    ozone_sigma_a: _rgb("Ozone Absorption", (0.650e-3, 1.881e-3, 0.085e-3),
                        "Atmosphere: the ozone's sigma_a at its centre, per scene unit")
    ozone_center_height: _length("Ozone Height", 25.0, "Atmosphere: the height of the "
                                 "ozone layer's centre")
    ozone_width: _length("Ozone Width", 30.0, "Atmosphere: the ozone layer's width (a "
                         "tent of density)", 1e-9)


def sweep_options(settings):
    """The gs_options fields (a dict for shafts.SweepRenderer) of a scene's
    ShaftsSweepSettings. Planes, Shadow Map and Light Map at 0 mean "the
    renderer decides" (by the light's kind, each map at its own size):
    they are left out, as the command line leaves out an option not given,
    since gs_options_set takes only explicit values (1 and up)."""
    options = {
        "planes": settings.planes,
        "lattice_u": settings.lattice,
        "lattice_v": settings.lattice,
        "light_map_res": settings.light_map_res,
        "shadow_map_res": settings.shadow_map_res,
        "xi": settings.xi.lower(),
        "jitter": int(settings.jitter),
        "sub_angle_deg": settings.sub_angle_deg,
        "sub_texels": settings.sub_texels,
    }
    return {key: value for key, value in options.items()
            if not (key in _RENDERER_DECIDES_AT_ZERO and value == 0)}


_RENDERER_DECIDES_AT_ZERO = ("planes", "shadow_map_res", "light_map_res")


def tracer_arguments(settings, spp=None):
    """(function name in shafts.py, keyword arguments) for a scene's
    ShaftsTracerSettings; spp overrides the samples (viewport refinement)."""
    spp = settings.spp if spp is None else spp
    common = {"spp": spp, "threads": settings.threads, "seed": settings.seed,
              "max_depth": settings.max_depth}
    if settings.mode == 'REFERENCE':
        return "render_reference", common
    args = dict(common, mode=settings.mode.lower(), refined=settings.refined,
                volume=settings.volume.lower())
    if settings.scheme != 'DEFAULT':
        args["scheme"] = settings.scheme.lower().replace("_", "-")
    if settings.mode == 'LMM':
        if settings.mesh_step > 0:
            args["mesh_step"] = settings.mesh_step
        args["radius"] = settings.radius
    return "render_lmm", args


classes = (ShaftsSweepSettings, ShaftsTracerSettings, ShaftsLightSettings,
           ShaftsMaterialSettings, ShaftsMediumSettings)


def register():
    bpy.types.Scene.shafts_sweep = PointerProperty(type=ShaftsSweepSettings)
    bpy.types.Scene.shafts_tracer = PointerProperty(type=ShaftsTracerSettings)
    bpy.types.Light.shafts = PointerProperty(type=ShaftsLightSettings)
    bpy.types.Material.shafts = PointerProperty(type=ShaftsMaterialSettings)
    bpy.types.Material.shafts_medium = PointerProperty(type=ShaftsMediumSettings)


def unregister():
    del bpy.types.Material.shafts_medium
    del bpy.types.Material.shafts
    del bpy.types.Light.shafts
    del bpy.types.Scene.shafts_tracer
    del bpy.types.Scene.shafts_sweep
