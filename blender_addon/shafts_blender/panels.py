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


class ShaftsPanel:
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'
    COMPAT_ENGINES = ENGINES

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


class SHAFTS_PT_sweep(ShaftsPanel, bpy.types.Panel):
    bl_label = "Plane Sweep"
    bl_context = "render"
    COMPAT_ENGINES = {"SHAFTS_SWEEP"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.shafts_sweep
        col = layout.column()
        col.prop(settings, "planes")
        col.prop(settings, "lattice")
        col.prop(settings, "xi")
        col.prop(settings, "jitter")
        col = layout.column(heading="Sub-Sampling")
        col.prop(settings, "sub_angle_deg")
        col.prop(settings, "sub_texels")
        col = layout.column(heading="Maps")
        col.prop(settings, "shadow_map_res")
        col.prop(settings, "light_map_res")


class SHAFTS_PT_tracer(ShaftsPanel, bpy.types.Panel):
    bl_label = "Tracer"
    bl_context = "render"
    COMPAT_ENGINES = {"SHAFTS_TRACER"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.shafts_tracer
        layout.prop(settings, "mode")
        col = layout.column()
        col.prop(settings, "spp")
        col.prop(settings, "viewport_spp")
        col.prop(settings, "max_depth")
        col.prop(settings, "seed")
        col.prop(settings, "threads")
        col = layout.column()
        col.active = settings.mode != 'REFERENCE'
        col.prop(settings, "scheme")
        col = layout.column()
        col.active = settings.mode == 'LMM'
        col.prop(settings, "refined")
        col.prop(settings, "mesh_step")
        col.prop(settings, "radius")
        col.prop(settings, "volume")


class SHAFTS_PT_light(ShaftsPanel, bpy.types.Panel):
    bl_label = "Shafts"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.light is not None

    def draw(self, context):
        self.layout.use_property_split = True
        self.layout.prop(context.light.shafts, "soft_shadows")


class SHAFTS_PT_material(ShaftsPanel, bpy.types.Panel):
    bl_label = "Shafts"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.material is not None

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        settings = context.material.shafts
        layout.prop(settings, "casts_soft_shadows")
        layout.prop(settings, "receives_soft_shadows")


classes = (SHAFTS_PT_sweep, SHAFTS_PT_tracer, SHAFTS_PT_light, SHAFTS_PT_material)


def register():
    for panel in shared_panels():
        panel.COMPAT_ENGINES.update(ENGINES)


def unregister():
    for panel in shared_panels():
        panel.COMPAT_ENGINES.difference_update(ENGINES)
