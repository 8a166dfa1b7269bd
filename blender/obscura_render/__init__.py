"""Obscura as a Blender render engine: the add-on's entry point.

A thin RenderEngine whose callbacks hand over to engine.py (as Cycles' add-on does); the
settings are in properties.py, the panels in ui.py, the scene translation in sync.py.
docs/BLENDER.md describes what maps to what.
"""

bl_info = {
    "name": "Obscura",
    "description": "Obscura, the Vulkan deferred renderer, as a render engine",
    "author": "Obscura",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > Obscura",
    "category": "Render",
}

import bpy

from . import engine, properties, ui


class ObscuraRenderEngine(bpy.types.RenderEngine):
    bl_idname = "OBSCURA"
    bl_label = "Obscura"
    bl_use_preview = False
    bl_use_postprocess = True
    bl_use_shading_nodes_custom = False  # Blender's own shader nodes (the Principled BSDF is translated)
    bl_use_eevee_viewport = True  # Material Preview shading stays EEVEE's

    def __init__(self):
        self.viewport = None

    def __del__(self):
        try:
            viewport = getattr(self, "viewport", None)
        except ReferenceError:  # Blender freed the engine's RNA first; the delegate goes with Python's objects
            return
        if viewport is not None:
            viewport.stage.close()

    def render(self, depsgraph):
        with engine.reported(self):
            engine.final_render(self, depsgraph)

    def update_render_passes(self, scene=None, renderlayer=None):
        engine.register_passes(self, scene, renderlayer)

    def view_update(self, context, depsgraph):
        with engine.reported(self):
            if self.viewport is None:
                self.viewport = engine.Viewport()
            self.viewport.update(self, depsgraph, context.region.width, context.region.height)

    def view_draw(self, context, depsgraph):
        if self.viewport is not None:
            with engine.reported(self):
                self.viewport.draw(self, context, depsgraph)


def register():
    properties.register()
    bpy.utils.register_class(ObscuraRenderEngine)
    ui.register()


def unregister():
    ui.unregister()
    bpy.utils.unregister_class(ObscuraRenderEngine)
    properties.unregister()
