"""The render settings artists change, as engine properties (Scene.obscura).

Each property is one Obscura render setting, labelled with the setting's name as ``obscura info``
lists it; its description and range are the plugin's. Defaults are the plugin's defaults
(delegate/render_settings.cpp), so a scene that never touched them renders as ``obscura render``.
"""

# No `from __future__ import annotations`: Blender reads the property annotations as objects.
import bpy

# Property name -> Obscura render setting name.
SETTINGS = {
    "msaa": "msaa",
    "taa": "taa",
    "taa_frames": "taa:frames",
    "ssao": "ssao",
    "shadows": "shadows",
    "dof": "dof",
    "motion_blur": "motionBlur",
    "motion_blur_samples": "motionBlur:samples",
    "exposure": "exposure",
    "ocio_look": "ocio:look",
}


class ObscuraRenderSettings(bpy.types.PropertyGroup):
    msaa: bpy.props.EnumProperty(name="msaa", description="Samples per pixel of the G-buffer",
                                 items=[("1", "1", "No multisampling"), ("4", "4", "4 samples per pixel")], default="1")
    taa: bpy.props.BoolProperty(name="taa", description="Temporal anti-aliasing (SMAA 1TX)", default=True)
    taa_frames: bpy.props.IntProperty(name="taa:frames", description="Frames a still image accumulates",
                                      default=16, min=1, max=1024)
    ssao: bpy.props.BoolProperty(name="ssao", description="Screen-space ambient occlusion on environment light",
                                 default=True)
    shadows: bpy.props.BoolProperty(name="shadows", description="Shadow maps", default=True)
    dof: bpy.props.BoolProperty(name="dof", description="Depth of field from the camera's lens", default=True)
    motion_blur: bpy.props.BoolProperty(name="motionBlur", description="Motion blur over the camera's shutter",
                                        default=True)
    motion_blur_samples: bpy.props.IntProperty(name="motionBlur:samples", description="Motion blur samples",
                                               default=8, min=2, max=32)
    exposure: bpy.props.FloatProperty(name="exposure", description="Exposure adjustment in stops", default=0.0)
    ocio_look: bpy.props.StringProperty(name="ocio:look", description="OCIO look (empty: none)", default="")

    def values(self) -> dict:
        """The render settings to set: Obscura's names and typed values."""
        out = {}
        for prop, setting in SETTINGS.items():
            value = getattr(self, prop)
            if prop == "msaa":
                value = int(value)
            if prop == "ocio_look" and not value:
                value = None  # the default: no look
            out[setting] = value
        return out


def register() -> None:
    bpy.utils.register_class(ObscuraRenderSettings)
    bpy.types.Scene.obscura = bpy.props.PointerProperty(type=ObscuraRenderSettings)


def unregister() -> None:
    del bpy.types.Scene.obscura
    bpy.utils.unregister_class(ObscuraRenderSettings)
