"""The add-on's panels, and Blender's own panels opened to its engines.

Blender's panels list the engines they draw for in COMPAT_ENGINES; the
engines join the panels every engine shares (output, format, colour
management: those that list BLENDER_RENDER) and the EEVEE panels whose
settings the converter reads (lights, materials' node surface and volume,
the world). Their own settings get their own panels.
"""
import bpy

ENGINES = {"SHAFTS_SWEEP", "SHAFTS_TRACER"}

# Blender's panels that show what the converter reads (names as in Blender
# 3.4's and 4.x's scripts/startup/bl_ui; a name missing in a version is
# skipped).
BLENDER_PANELS = (
    "DATA_PT_context_light", "DATA_PT_preview", "DATA_PT_light", "DATA_PT_EEVEE_light",
    "DATA_PT_EEVEE_light_distance", "DATA_PT_spot", "DATA_PT_context_camera", "DATA_PT_lens",
    "DATA_PT_camera", "DATA_PT_camera_display", "DATA_PT_camera_safe_areas",
    "EEVEE_MATERIAL_PT_context_material", "EEVEE_MATERIAL_PT_surface",
    "EEVEE_MATERIAL_PT_volume", "EEVEE_MATERIAL_PT_settings",
    "EEVEE_WORLD_PT_surface", "EEVEE_WORLD_PT_volume", "WORLD_PT_context_world",
    "MATERIAL_PT_preview", "WORLD_PT_viewport_display", "MATERIAL_PT_viewport",
    "RENDER_PT_color_management", "RENDER_PT_color_management_curves",
)
# Panels of every engine that show nothing our engines use.
EXCLUDED = {"VIEWLAYER_PT_filter", "VIEWLAYER_PT_layer_passes"}


def shared_panels():
    found = []
    for panel in bpy.types.Panel.__subclasses__():
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if engines is None or panel.__name__ in EXCLUDED:
            continue
        if "BLENDER_RENDER" in engines or panel.__name__ in BLENDER_PANELS:
            found.append(panel)
    return found


def draw_groups(layout, settings, groups):
    """Draws settings as columns: groups of (heading or None, a function of
    the settings telling whether the group applies, or None, property
    names)."""
    layout.use_property_split = True
    layout.use_property_decorate = False
    for heading, applies, names in groups:
        col = layout.column(heading=heading) if heading else layout.column()
        if applies is not None:
            col.active = applies(settings)
        for name in names:
            col.prop(settings, name)


class ShaftsPanel:
    """A panel of the add-on's settings: the property group ``SETTINGS`` of
    the context's ``DATA`` (the scene, the light, the material), drawn as
    ``GROUPS`` (draw_groups); shown when one of our engines renders and the
    context has that data."""
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'
    COMPAT_ENGINES = ENGINES
    DATA = "scene"
    SETTINGS = "shafts"
    GROUPS = ()

    @classmethod
    def poll(cls, context):
        return (context.engine in cls.COMPAT_ENGINES
                and getattr(context, cls.DATA, None) is not None)

    def draw(self, context):
        data = getattr(context, self.DATA)
        draw_groups(self.layout, getattr(data, self.SETTINGS), self.GROUPS)


class SHAFTS_PT_sweep(ShaftsPanel, bpy.types.Panel):
    bl_label = "Plane Sweep"
    bl_context = "render"
    COMPAT_ENGINES = {"SHAFTS_SWEEP"}
    SETTINGS = "shafts_sweep"
    GROUPS = ((None, None, ("planes", "lattice", "xi", "jitter", "viewport_divider")),
              ("Sub-Sampling", None, ("sub_angle_deg", "sub_texels")),
              ("Maps", None, ("shadow_map_res", "light_map_res")))


class SHAFTS_PT_tracer(ShaftsPanel, bpy.types.Panel):
    bl_label = "Tracer"
    bl_context = "render"
    COMPAT_ENGINES = {"SHAFTS_TRACER"}
    SETTINGS = "shafts_tracer"
    GROUPS = ((None, None, ("mode",)),
              (None, None, ("spp", "viewport_spp", "viewport_divider", "max_depth", "seed",
                            "threads")),
              (None, lambda s: s.mode != 'REFERENCE', ("scheme",)),
              # Refined is a variant of refract-both: greyed out under any
              # other scheme, where the library refuses it.
              (None, lambda s: s.mode == 'LMM' and s.scheme == 'REFRACT_BOTH', ("refined",)),
              (None, lambda s: s.mode == 'LMM', ("mesh_step", "radius", "volume")))


class SHAFTS_PT_light(ShaftsPanel, bpy.types.Panel):
    bl_label = "Shafts"
    bl_context = "data"
    DATA = "light"
    GROUPS = ((None, None, ("soft_shadows",)),)


class SHAFTS_PT_material(ShaftsPanel, bpy.types.Panel):
    bl_label = "Shafts"
    bl_context = "material"
    DATA = "material"
    GROUPS = ((None, None, ("casts_soft_shadows", "receives_soft_shadows")),)


class SHAFTS_PT_medium(ShaftsPanel, bpy.types.Panel):
    """The medium a volume material stands for (material.shafts_medium,
    properties.ShaftsMediumSettings): only the chosen kind's settings are
    drawn."""
    bl_label = "Shafts Medium"
    bl_context = "material"
    DATA = "material"
    SETTINGS = "shafts_medium"
    KINDS = {
        'NODES': (),
        'HEIGHT_FOG': ((None, None, ("sigma_s", "sigma_a")),
                       (None, None, ("base_height", "scale_height")),
                       (None, None, ("phase",)),
                       (None, lambda s: s.phase in ('HENYEY_GREENSTEIN', 'CORNETTE_SHANKS'),
                        ("phase_g",))),
        'ATMOSPHERE': ((None, None, ("center", "ground_radius", "top_radius",
                                     "ground_albedo")),
                       ("Rayleigh", None, ("rayleigh_sigma_s", "rayleigh_scale_height")),
                       (None, None, ("use_mie",)),
                       (None, lambda s: s.use_mie, ("mie_sigma_s", "mie_sigma_a",
                                                    "mie_scale_height", "mie_phase")),
                       (None, lambda s: s.use_mie and s.mie_phase in (
                           'HENYEY_GREENSTEIN', 'CORNETTE_SHANKS'), ("mie_g",)),
                       (None, None, ("use_ozone",)),
                       (None, lambda s: s.use_ozone, ("ozone_sigma_a", "ozone_center_height",
                                                      "ozone_width"))),
    }

    def draw(self, context):
        settings = context.material.shafts_medium
        draw_groups(self.layout, settings,
                    ((None, None, ("kind",)),) + self.KINDS[settings.kind])


classes = (SHAFTS_PT_sweep, SHAFTS_PT_tracer, SHAFTS_PT_light, SHAFTS_PT_material,
           SHAFTS_PT_medium)


def register():
    for panel in shared_panels():
        panel.COMPAT_ENGINES.update(ENGINES)


def unregister():
    for panel in shared_panels():
        panel.COMPAT_ENGINES.difference_update(ENGINES)
