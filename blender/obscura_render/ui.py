"""Panels: Obscura's render settings, and where the plugin was (or was not) found."""

from __future__ import annotations

import bpy

from . import engine, properties


class OBSCURA_PT_render_settings(bpy.types.Panel):
    bl_label = "Obscura"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"OBSCURA"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        layout = self.layout
        status = engine.plugin_status()
        if status.error:
            box = layout.box()
            box.alert = True
            box.label(text="Obscura plugin not found", icon="ERROR")
            for line in status.error.split(". "):
                box.label(text=line)
        elif status.library:
            layout.label(text=f"Plugin: {status.library}", icon="PLUGIN")
        settings = context.scene.obscura
        layout.use_property_split = True
        for prop in properties.SETTINGS:
            layout.prop(settings, prop)
        # The shutter is Blender's own (Cycles reads the same properties).
        layout.prop(context.scene.render, "use_motion_blur")
        layout.prop(context.scene.render, "motion_blur_shutter")


CLASSES = (OBSCURA_PT_render_settings,)


def _compatible_panels():
    """Blender's own panels that apply to any engine (dimensions, output, colour management, passes)."""
    names = ["RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_output", "RENDER_PT_color_management",
             "VIEWLAYER_PT_layer_passes", "DATA_PT_lens", "DATA_PT_camera", "DATA_PT_camera_dof",
             "DATA_PT_camera_dof_aperture", "DATA_PT_light", "DATA_PT_EEVEE_light", "DATA_PT_EEVEE_light_distance",
             "DATA_PT_spot", "MATERIAL_PT_preview", "EEVEE_MATERIAL_PT_context_material",
             "EEVEE_MATERIAL_PT_surface", "MATERIAL_PT_viewport", "WORLD_PT_context_world", "EEVEE_WORLD_PT_surface",
             "OBJECT_PT_relations"]
    panels = (getattr(bpy.types, n, None) for n in names)
    return [p for p in panels if p is not None and hasattr(p, "COMPAT_ENGINES")]


def register() -> None:
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.add("OBSCURA")


def unregister() -> None:
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.discard("OBSCURA")
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
