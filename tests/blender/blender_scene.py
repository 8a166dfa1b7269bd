"""What the add-on's tests in Blender share: the add-on installed from its zip, the add-on's log
captured, scenes built in Python and the checks' failures."""

from __future__ import annotations

import logging

import bpy


class Captured(logging.Handler):
    """The add-on's log (its own messages and the plugin's)."""

    def __init__(self):
        super().__init__(logging.DEBUG)
        self.records: list[logging.LogRecord] = []

    def emit(self, record):
        self.records.append(record)

    def messages(self, level: int) -> list[str]:
        return [r.getMessage() for r in self.records if r.levelno == level]


LOG = Captured()
logging.getLogger("obscura_render").addHandler(LOG)
logging.getLogger("obscura_render").setLevel(logging.DEBUG)


def install_addon(zip_path: str) -> None:
    """As an artist installs it (Preferences > Add-ons > Install...), then the add-on's way to the
    Python package, which the tests import too."""
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    bpy.ops.preferences.addon_enable(module="obscura_render")
    from obscura_render import locate

    locate.import_package()


def expect(condition, message):
    if not condition:
        raise AssertionError(message)


def expect_no_plugin_errors():
    errors = LOG.messages(logging.ERROR)
    expect(not errors, f"errors logged: {errors}")


def empty_scene(size: int):
    """An empty scene rendered by Obscura at size x size pixels, two TAA frames, no world."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "OBSCURA"
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.obscura.taa_frames = 2
    scene.world = None
    return scene


def link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


def principled(name, albedo):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (albedo, albedo, albedo, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Metallic"].default_value = 0.0
    bsdf.inputs["Specular"].default_value = 0.0  # F0 = 0: the Lambert term alone, in Cycles too
    return material


def add_plane(name, half, material, pass_index=0):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    obj = link(bpy.data.objects.new(name, mesh))
    obj.pass_index = pass_index
    return obj


def add_light(kind, energy, **settings):
    data = bpy.data.lights.new(kind, kind)
    data.energy = energy
    data.specular_factor = 0.0  # diffuse only: the Lambert term alone
    for key, value in settings.items():
        setattr(data, key, value)
    return link(bpy.data.objects.new(kind, data))
