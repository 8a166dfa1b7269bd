"""The Blender add-on, headless: installed from its zip as an artist installs it, scenes built
in Python, rendered with F12's operator, the Render Result's passes read back through the
compositor and checked against physics.

    blender -b --factory-startup --python-exit-code 1 --python addon_test.py -- ADDON_ZIP TESTS_PYTHON_DIR

TESTS_PYTHON_DIR is tests/python (lit_plane.py: the albedo the G-buffer stores exactly and the
radiance tolerance of the light buffer's format). OBSCURA_PLUGINPATH names the plugin;
OBSCURA_VALIDATION=1 keeps the Vulkan validation layer on.
"""

from __future__ import annotations

import logging
import math
import os
import sys
import tempfile
import traceback
from pathlib import Path

import bpy
import numpy as np

ZIP, TESTS_PYTHON = sys.argv[sys.argv.index("--") + 1:][:2]
sys.path[:0] = [TESTS_PYTHON, str(Path(__file__).resolve().parent)]
import blender_scene  # noqa: E402
from blender_scene import LOG, add_light, add_plane, expect, expect_no_plugin_errors, link, principled  # noqa: E402
SIZE = 64
CAMERA_DISTANCE = 5.0
LENS, SENSOR = 50.0, 36.0


# --- scenes -------------------------------------------------------------------------------------

def empty_scene():
    return blender_scene.empty_scene(SIZE)


def add_camera(scene, lens=LENS, shift_x=0.0):
    data = bpy.data.cameras.new("Camera")
    data.lens, data.sensor_width, data.sensor_fit = lens, SENSOR, "AUTO"
    data.shift_x = shift_x
    data.clip_start, data.clip_end = 0.1, 100.0
    camera = link(bpy.data.objects.new("Camera", data))
    camera.location = (0.0, 0.0, CAMERA_DISTANCE)  # unrotated: looking down -Z
    scene.camera = camera
    return camera


# --- rendering ----------------------------------------------------------------------------------

PASS_SOCKETS = {"Image": "Image", "Depth": "Depth", "Normal": "Normal", "IndexOB": "IndexOB", "Vector": "Vector"}


def render_passes(scene, passes=("Image",)) -> dict[str, np.ndarray]:
    """F12 (render.render), every pass written by a compositor File Output node as a float EXR and
    read back: name -> (SIZE, SIZE, 4) array, bottom row first as Blender stores images."""
    layer = scene.view_layers[0]
    layer.use_pass_z = "Depth" in passes
    layer.use_pass_normal = "Normal" in passes
    layer.use_pass_object_index = "IndexOB" in passes
    layer.use_pass_vector = "Vector" in passes
    scene.use_nodes = True
    scene.render.use_compositing = True
    tree = scene.node_tree
    tree.nodes.clear()
    source = tree.nodes.new("CompositorNodeRLayers")
    out = tree.nodes.new("CompositorNodeOutputFile")
    folder = tempfile.mkdtemp(prefix="obscura-blender-")
    out.base_path = folder
    out.format.file_format = "OPEN_EXR"
    out.format.color_depth = "32"
    out.format.color_mode = "RGBA"
    out.file_slots.clear()
    for name in passes:
        out.file_slots.new(name)
        tree.links.new(source.outputs[PASS_SOCKETS[name]], out.inputs[name])
    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(source.outputs["Image"], composite.inputs["Image"])
    bpy.ops.render.render()
    images = {}
    for name in passes:
        image = bpy.data.images.load(str(Path(folder) / f"{name}{scene.frame_current:04d}.exr"))
        pixels = np.empty(SIZE * SIZE * 4, np.float32)
        image.pixels.foreach_get(pixels)
        images[name] = pixels.reshape(SIZE, SIZE, 4)
        bpy.data.images.remove(image)
    return images


# --- tests --------------------------------------------------------------------------------------

def test_missing_plugin_is_said_in_the_log_and_the_panel():
    # An empty search path and no installed plugin (skipped where one is installed).
    if any(Path(p).exists() for p in ("/usr/lib/obscura/plugin", "/usr/local/lib/obscura/plugin")):
        print("skipped: an installed plugin would be found")
        return
    from obscura_render import engine

    saved = os.environ["OBSCURA_PLUGINPATH"]
    os.environ["OBSCURA_PLUGINPATH"] = tempfile.mkdtemp(prefix="obscura-no-plugin-")
    try:
        scene = empty_scene()
        add_camera(scene)
        bpy.ops.render.render()
        raise AssertionError("rendered without a plugin")
    except RuntimeError as e:  # the render's ERROR report, which Blender shows in its status bar
        expect("OBSCURA_PLUGINPATH" in str(e), str(e))
    finally:
        os.environ["OBSCURA_PLUGINPATH"] = saved
    errors = LOG.messages(logging.ERROR)
    expect(len(errors) == 1 and "plugin" in errors[0] and "OBSCURA_PLUGINPATH" in errors[0], errors)
    expect(engine.plugin_status().error == errors[0], "the panel shows the message")
    LOG.records.clear()


def test_installed_from_the_zip_with_its_own_python_package():
    import obscura
    import obscura_render

    addon = Path(obscura_render.__file__).resolve().parent
    expect(Path(bpy.utils.user_resource("SCRIPTS")).resolve() in addon.parents, f"installed add-on at {addon}")
    expect(Path(obscura.__file__).resolve().is_relative_to(addon / "vendor"), obscura.__file__)


def test_sun_on_a_lambert_plane_and_the_passes():
    """Radiance L = albedo / pi * E cos(theta), with E the illuminance of the converted sun:
    Strength / 4 (Blender's USD exporter). Depth, Normal and IndexOB of a plane facing the camera."""
    from lit_plane import ALBEDO, radiance_tolerance

    scene = empty_scene()
    add_camera(scene)
    half = 1.0
    add_plane("Plane", half, principled("Grey", ALBEDO), pass_index=3)
    strength, theta = 4.0, math.radians(30.0)
    sun = add_light("SUN", strength, angle=0.0)
    sun.rotation_euler = (0.0, theta, 0.0)  # local -Z tilted by theta off the plane's normal
    images = render_passes(scene, ("Image", "Depth", "Normal", "IndexOB"))
    expected = ALBEDO / math.pi * (strength / 4.0) * math.cos(theta)
    centre = images["Image"][SIZE // 2 - 4:SIZE // 2 + 4, SIZE // 2 - 4:SIZE // 2 + 4]
    for c in range(3):
        error = np.abs(centre[..., c] - expected).max()
        expect(error <= radiance_tolerance(expected, c), f"channel {c}: {centre[..., c].ravel()[:4]} vs {expected}")
    # Framing: the plane's image is 2 half f / (D sensor) of the frame's width (pinhole camera).
    depth = images["Depth"][..., 0]
    covered = np.isfinite(depth) & (depth < 1e9)
    width_px = covered[SIZE // 2].sum()
    expected_px = 2 * half * LENS / (CAMERA_DISTANCE * SENSOR) * SIZE
    expect(abs(width_px - expected_px) <= 1.0, f"plane {width_px} px wide, {expected_px:.2f} expected")
    expect(np.allclose(depth[covered], CAMERA_DISTANCE, rtol=1e-3), f"depth {depth[covered][:4]}")
    normal = images["Normal"][..., :3][covered]
    expect(np.allclose(normal, (0.0, 0.0, 1.0), atol=1e-2), f"world normal {normal[:2]}")
    expect(np.all(images["IndexOB"][..., 0][covered] == 3.0), "IndexOB is the pass index")
    expect(np.all(images["IndexOB"][..., 0][~covered] == 0.0), "IndexOB is 0 where nothing drew")
    expect_no_plugin_errors()


def test_image_texture_on_base_color():
    """An Image Texture node on Base Color: a uniform sRGB PNG of code 188 is the albedo the
    untextured plane had, so the radiance is the same."""
    from lit_plane import ALBEDO, radiance_tolerance

    scene = empty_scene()
    add_camera(scene)
    material = principled("Textured", 0.0)  # black unless the texture is read
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(uniform_png("uniform", (188, 188, 188)))
    material.node_tree.links.new(texture.outputs["Color"],
                                 material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    add_plane("Plane", 10.0, material)
    strength = 4.0
    add_light("SUN", strength, angle=0.0)
    image = render_passes(scene)["Image"]
    expected = ALBEDO / math.pi * strength / 4.0
    for c in range(3):
        value = image[SIZE // 2, SIZE // 2, c]
        expect(abs(value - expected) <= radiance_tolerance(expected, c), f"channel {c}: {value} vs {expected}")
    expect_no_plugin_errors()


def test_world_colour_as_a_dome():
    """A world of constant radiance Lw: the camera sees Lw where nothing is drawn, and a Lambert
    plane under the open sky (irradiance pi Lw) reflects albedo x Lw."""
    from lit_plane import ALBEDO, radiance_tolerance

    scene = empty_scene()
    scene.obscura.ssao = False  # ambient occlusion would darken the dome's light
    scene.world = bpy.data.worlds.new("Sky")
    scene.world.use_nodes = False
    radiance = 0.5
    scene.world.color = (radiance, radiance, radiance)
    add_camera(scene)
    add_plane("Plane", 1.0, principled("Grey", ALBEDO))
    image = render_passes(scene)["Image"]
    expected = ALBEDO * radiance
    for c in range(3):
        lit, sky = image[SIZE // 2, SIZE // 2, c], image[2, 2, c]
        expect(abs(lit - expected) <= radiance_tolerance(expected, c), f"plane {c}: {lit} vs {expected}")
        expect(abs(sky - radiance) <= radiance_tolerance(radiance, c), f"sky {c}: {sky} vs {radiance}")
    expect_no_plugin_errors()


def uniform_png(name, rgb_codes) -> str:
    """A 8 x 8 PNG of one colour (8-bit codes), as a file on disk."""
    generated = bpy.data.images.new(name, 8, 8, alpha=False)
    generated.pixels.foreach_set(np.tile([c / 255 for c in rgb_codes] + [1.0], 64).astype(np.float32))
    path = str(Path(tempfile.mkdtemp(prefix="obscura-texture-")) / f"{name}.png")
    generated.filepath_raw, generated.file_format = path, "PNG"
    generated.save()
    return path


def test_normal_map_tilts_the_shading_normal():
    """A tangent-space normal map of one texel (191, 128, 238): n = 2 t - 1, about 30 degrees off
    the surface normal; under a sun straight overhead the radiance is albedo / pi x E x n_z / |n|."""
    from lit_plane import ALBEDO, radiance_tolerance

    scene = empty_scene()
    add_camera(scene)
    material = principled("Bumpy", ALBEDO)
    tree = material.node_tree
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(uniform_png("normal", (191, 128, 238)))
    texture.image.colorspace_settings.name = "Non-Color"
    normal_map = tree.nodes.new("ShaderNodeNormalMap")
    tree.links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    tree.links.new(normal_map.outputs["Normal"], tree.nodes["Principled BSDF"].inputs["Normal"])
    plane = add_plane("Plane", 10.0, material)
    plane.data.uv_layers.new(name="UVMap")
    strength = 4.0
    add_light("SUN", strength, angle=0.0)
    image = render_passes(scene)["Image"]
    n = np.array([191, 128, 238]) / 255 * 2 - 1
    expected = ALBEDO / math.pi * strength / 4.0 * n[2] / np.linalg.norm(n)
    flat = ALBEDO / math.pi * strength / 4.0
    value = image[SIZE // 2, SIZE // 2, 0]
    expect(abs(value - expected) <= radiance_tolerance(expected, 0), f"{value} vs {expected} (flat: {flat})")
    expect_no_plugin_errors()


def test_point_light_at_a_known_distance():
    """A normalised sphere light of intensity P / pi (P the Blender power) gives E = P / (4 pi d^2)
    on a surface facing it at distance d: L = albedo / pi * E."""
    from lit_plane import ALBEDO, radiance_tolerance

    scene = empty_scene()
    add_camera(scene)
    add_plane("Plane", 10.0, principled("Grey", ALBEDO))
    power, height = 100.0, 2.0
    point = add_light("POINT", power, shadow_soft_size=0.05)
    point.location = (0.0, 0.0, height)
    image = render_passes(scene)["Image"]
    # The pixel whose centre sees the plane point nearest the light's foot: distance d, normal incidence.
    tan_half = SENSOR / 2 / LENS
    x = y = SIZE // 2
    offset = ((x + 0.5) / SIZE * 2 - 1) * tan_half * CAMERA_DISTANCE
    r2 = 2 * offset * offset + height * height
    expected = ALBEDO / math.pi * power / (4 * math.pi * r2) * (height / math.sqrt(r2))
    for c in range(3):
        value = image[y, x, c]
        expect(abs(value - expected) <= radiance_tolerance(expected, c), f"channel {c}: {value} vs {expected}")
    expect_no_plugin_errors()


def test_spot_light_cone_from_the_spot_size():
    """A spot of Size 60 degrees (cone half-angle 30, Blend 0) straight above the plane at height h
    lights the disc of radius h tan(30) like a point light of the same power, and nothing outside."""
    from lit_plane import ALBEDO, radiance_tolerance

    scene = empty_scene()
    add_camera(scene)
    add_plane("Plane", 10.0, principled("Grey", ALBEDO))
    power, height = 100.0, 2.0
    spot = add_light("SPOT", power, shadow_soft_size=0.05, spot_size=math.radians(60.0), spot_blend=0.0)
    spot.location = (0.0, 0.0, height)
    image = render_passes(scene)["Image"][..., 0]
    metres_per_px = 2 * (SENSOR / 2 / LENS) * CAMERA_DISTANCE / SIZE
    edge_px = height * math.tan(math.radians(30.0)) / metres_per_px  # the cone's edge, from the centre
    centre = SIZE / 2
    x = np.arange(SIZE) + 0.5 - centre
    radius = np.hypot(x[None, :], x[:, None])
    expected = ALBEDO / math.pi * power / (4 * math.pi * height * height)
    inside, outside = image[radius < edge_px - 2], image[radius > edge_px + 2]
    expect(abs(image[SIZE // 2, SIZE // 2] - expected) <= radiance_tolerance(expected, 0),
           f"centre {image[SIZE // 2, SIZE // 2]} vs {expected}")
    expect(inside.min() > 0.0 and outside.max() == 0.0, f"inside min {inside.min()}, outside max {outside.max()}")
    expect_no_plugin_errors()


def test_point_and_sun_against_cycles_direct_light():
    """The same scenes in Cycles, direct light only: a point light agrees (both E = P / (4 pi d^2));
    a sun is four times brighter in Cycles (E = Strength), the factor of Blender's USD exporter."""
    from lit_plane import ALBEDO, radiance_tolerance

    def centre(engine, light, energy, **settings):
        scene = empty_scene()
        scene.render.engine = engine
        scene.cycles.samples, scene.cycles.max_bounces, scene.cycles.use_denoising = 256, 0, False
        scene.cycles.seed = 1
        add_camera(scene)
        add_plane("Plane", 10.0, principled("Grey", ALBEDO))
        add_light(light, energy, **settings).location = (0.0, 0.0, 2.0)
        patch = render_passes(scene)["Image"][SIZE // 2 - 2:SIZE // 2 + 2, SIZE // 2 - 2:SIZE // 2 + 2, 0]
        return patch.mean(), patch.std() / math.sqrt(patch.size)

    for light, energy, settings, cycles_over_obscura in (("POINT", 100.0, {"shadow_soft_size": 0.05}, 1.0),
                                                         ("SUN", 4.0, {"angle": 0.0}, 4.0)):
        obscura_value, _ = centre("OBSCURA", light, energy, **settings)
        cycles_value, cycles_error = centre("CYCLES", light, energy, **settings)
        expected = cycles_value / cycles_over_obscura
        tolerance = radiance_tolerance(expected, 0) + 3.0 * cycles_error / cycles_over_obscura
        expect(abs(obscura_value - expected) <= tolerance,
               f"{light}: Obscura {obscura_value}, Cycles {cycles_value} / {cycles_over_obscura}")
    expect_no_plugin_errors()


def test_camera_shift_moves_the_image_by_the_shift_times_the_frame():
    scene = empty_scene()
    add_camera(scene, shift_x=0.25)
    add_plane("Plane", 1.0, principled("Grey", 0.5))
    add_light("SUN", 4.0)
    depth = render_passes(scene, ("Image", "Depth"))["Depth"][SIZE // 2, :, 0]
    covered = np.flatnonzero(np.isfinite(depth) & (depth < 1e9))
    centre = (covered[0] + covered[-1] + 1) / 2
    # Shifting the film right by 0.25 of its width moves the image left by a quarter of the frame.
    expect(abs(centre - (SIZE / 2 - 0.25 * SIZE)) <= 1.0, f"image centred at {centre}")


def test_principled_anisotropy_feeds_the_anisotropic_lobe():
    from obscura_render import materials

    material = principled("Brushed", 0.5)
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Anisotropic"].default_value = 0.6
    bsdf.inputs["Anisotropic Rotation"].default_value = 0.25  # a quarter turn
    values = materials.principled_values(bsdf)
    expect(math.isclose(values["inputs:obscura:anisotropy"], 0.6, rel_tol=1e-6), values["inputs:obscura:anisotropy"])
    expect(math.isclose(values["inputs:obscura:anisotropyRotation"], 90.0, rel_tol=1e-6),
           values["inputs:obscura:anisotropyRotation"])


def test_mapping_node_becomes_the_textures_coordinate_transform():
    """A Point Mapping node before an Image Texture: location + rotate(Z) (scale uv), as Blender's
    USD exporter writes it into a UsdTransform2d; a rotation about X is no 2D transform."""
    from obscura_render import materials

    material = principled("Mapped", 0.5)
    tree = material.node_tree
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(uniform_png("mapped", (188, 188, 188)))
    tree.links.new(texture.outputs["Color"], tree.nodes["Principled BSDF"].inputs["Base Color"])
    mapping = tree.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Location"].default_value = (0.25, 0.5, 0.0)
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.pi / 2)
    mapping.inputs["Scale"].default_value = (2.0, 3.0, 1.0)
    tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    values = materials.principled_values(tree.nodes["Principled BSDF"])
    # rotate(90 degrees) (2 u, 3 v) = (-3 v, 2 u), then moved by the location.
    for row, expected in (("transformS", (0.0, -3.0, 0.25)), ("transformT", (2.0, 0.0, 0.5))):
        got = values[f"obscura:diffuseColor:{row}"]
        expect(all(math.isclose(g, e, abs_tol=1e-6) for g, e in zip(got, expected)), f"{row}: {got} vs {expected}")
    mapping.inputs["Rotation"].default_value = (0.3, 0.0, 0.0)
    try:
        materials.principled_values(tree.nodes["Principled BSDF"])
        expect(False, "a rotation about X maps")
    except materials.Unsupported as e:
        expect("rotates about X or Y" in str(e), str(e))


def test_unsupported_nodes_fall_back_with_one_warning_naming_the_material():
    scene = empty_scene()
    add_camera(scene)
    material = bpy.data.materials.new("Glowing")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    material.node_tree.links.new(emission.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    material.diffuse_color = (0.2, 0.4, 0.6, 1.0)
    for i in range(2):
        plane = add_plane(f"Plane{i}", 0.5, material)
        plane.location.x = -1.0 + 2.0 * i
    add_light("SUN", 4.0)
    LOG.records.clear()
    render_passes(scene)
    warnings = [w for w in LOG.messages(logging.WARNING) if "Glowing" in w]
    expect(len(warnings) == 1 and "viewport display colour" in warnings[0], f"warnings: {warnings}")
    expect_no_plugin_errors()


def test_an_edit_resyncs_only_that_prim():
    """view_update's path: after a full sync, moving an object, changing a light or a material
    marks only that prim dirty, and the delegate syncs only it."""
    from obscura_render import engine

    scene = empty_scene()
    add_camera(scene)
    grey = principled("Grey", 0.5)
    moved = add_plane("Moved", 0.5, grey)
    add_plane("Still", 0.5, grey).location.x = 1.5
    sun = add_light("SUN", 4.0)
    stage = engine.Stage()
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        stage.sync.sync(depsgraph, SIZE, SIZE)
        stage.set_buffers(SIZE, SIZE, ["color"])
        stage.render(0.0)
        total = stage.delegate.stats.prims_synced
        dirtied = []
        handler = lambda _scene, graph: dirtied.append(stage.sync.update(graph))  # noqa: E731
        bpy.app.handlers.depsgraph_update_post.append(handler)
        roughness = grey.node_tree.nodes["Principled BSDF"].inputs["Roughness"]
        edits = {"move an object": lambda: setattr(moved.location, "x", -1.0),
                 "change the sun": lambda: setattr(sun.data, "energy", 2.0),
                 "change the material": lambda: setattr(roughness, "default_value", 0.5)}
        try:
            for what, edit in edits.items():
                dirtied.clear()
                edit()
                bpy.context.view_layer.update()
                stage.render(0.0)
                synced = stage.delegate.stats.prims_synced
                expect(dirtied == [1], f"{what}: prims marked dirty: {dirtied}")
                expect(synced == 1 and total > 1, f"{what}: prims synced: {synced} after it, {total} at first")
        finally:
            bpy.app.handlers.depsgraph_update_post.remove(handler)
        expect(stage.delegate.stats.validation_errors == 0, "validation errors")
    finally:
        stage.close()
    expect_no_plugin_errors()


def synced_prims(scene) -> dict:
    """The prims the add-on makes of the scene: path -> obscura.scene.Prim (no render)."""
    from obscura_render import engine

    stage = engine.Stage()
    try:
        stage.sync.sync(bpy.context.evaluated_depsgraph_get(), *engine.render_size(scene))
        return dict(stage.delegate.scene.prims)
    finally:
        stage.close()


def value(prim, name):
    """A numeric attribute: a number (bools as 0/1), or one row per element of an array."""
    held = prim.values[name]
    if held.is_array:
        return held.array.reshape(held.count, -1)
    return held.array.item() if held.array.size == 1 else held.array.tolist()


def test_light_types_and_sizes_as_blenders_usd_exporter_writes_them():
    """usd_writer_light.cc: sun energy / 4, the others energy / pi, all normalised; spot cone half
    the spot size; disk radius half the size; rectangles their sizes."""
    scene = empty_scene()
    add_light("SUN", 8.0, angle=math.radians(2.0))
    add_light("POINT", 50.0, shadow_soft_size=0.25)
    add_light("SPOT", 30.0, shadow_soft_size=0.1, spot_size=math.radians(60.0), spot_blend=0.2)
    add_light("AREA", 20.0, shape="RECTANGLE", size=2.0, size_y=0.5).name = "Rect"
    add_light("AREA", 10.0, shape="DISK", size=1.0).name = "Disk"
    add_light("AREA", 10.0, shape="SQUARE", size=1.5).name = "Square"
    add_light("AREA", 10.0, shape="ELLIPSE", size=1.0, size_y=2.0).name = "Ellipse"
    add_light("POINT", 1.0).name, add_light("POINT", 2.0).name = "Lamp.1", "Lamp_1"  # two names, two prims
    prims = synced_prims(scene)
    sun, point, spot = prims["/Lights/SUN"], prims["/Lights/POINT"], prims["/Lights/SPOT"]
    rect, disk = prims["/Lights/Rect"], prims["/Lights/Disk"]
    expect((sun.type, point.type, spot.type, rect.type, disk.type) ==
           ("distantLight", "sphereLight", "sphereLight", "rectLight", "diskLight"), "light types")
    close = lambda a, b: abs(a - b) <= 1e-5 * max(1.0, abs(b))  # noqa: E731
    for prim, intensity in ((sun, 2.0), (point, 50.0 / math.pi), (spot, 30.0 / math.pi), (rect, 20.0 / math.pi),
                            (disk, 10.0 / math.pi)):
        expect(close(value(prim, "inputs:intensity"), intensity), f"intensity {value(prim, 'inputs:intensity')}")
        expect(value(prim, "inputs:normalize") == 1, "normalized")
    expect(close(value(sun, "inputs:angle"), 2.0), "sun angle")
    expect(close(value(point, "inputs:radius"), 0.25), "point radius")
    expect(close(value(spot, "inputs:shaping:cone:angle"), 30.0), "spot cone")
    expect(close(value(spot, "inputs:shaping:cone:softness"), 0.2), "spot blend")
    expect(close(value(rect, "inputs:width"), 2.0) and close(value(rect, "inputs:height"), 0.5), "rect size")
    expect(close(value(disk, "inputs:radius"), 0.5), "disk radius")
    square, ellipse = prims["/Lights/Square"], prims["/Lights/Ellipse"]
    expect(square.type == "rectLight" and close(value(square, "inputs:width"), 1.5)
           and close(value(square, "inputs:height"), 1.5), "square")
    expect(ellipse.type == "diskLight" and close(value(ellipse, "inputs:radius"), 0.75), "ellipse: mean diameter")
    lamps = sorted(value(p, "inputs:intensity") * math.pi for path, p in prims.items()
                   if path.startswith("/Lights/Lamp"))
    expect(len(lamps) == 2 and close(lamps[0], 1.0) and close(lamps[1], 2.0), f"Lamp.1 and Lamp_1: {lamps}")


def test_camera_lens_and_depth_of_field():
    """Film back in tenths of a scene unit (usd_writer_camera.cc: lens / (100 mm per metre unit)),
    the sensor on the larger side, focus distance from a focus object along the view axis."""
    scene = empty_scene()
    scene.render.resolution_x, scene.render.resolution_y = 2 * SIZE, SIZE
    camera = add_camera(scene, lens=35.0)
    target = link(bpy.data.objects.new("Target", None))
    target.location = (1.0, 0.5, -3.0)  # 8 in front of the camera at z = 5, off axis
    dof = camera.data.dof
    dof.use_dof, dof.aperture_fstop, dof.focus_object = True, 2.8, target
    dof.aperture_blades, dof.aperture_rotation = 6, math.radians(15.0)
    prim = synced_prims(scene)["/Camera"]
    close = lambda a, b: abs(a - b) <= 1e-5 * max(1.0, abs(b))  # noqa: E731
    expect(close(value(prim, "focalLength"), 0.35), f"focal length {value(prim, 'focalLength')}")
    expect(close(value(prim, "horizontalAperture"), 0.36), "horizontal aperture")
    expect(close(value(prim, "verticalAperture"), 0.18), "vertical aperture")
    expect(close(value(prim, "fStop"), 2.8) and close(value(prim, "focusDistance"), 8.0), "f-stop, focus")
    expect(value(prim, "obscura:apertureBlades") == 6, "blades")
    expect(close(value(prim, "obscura:apertureRotation"), 15.0), "aperture rotation")


def test_viewport_camera_from_the_projection_matches_the_camera():
    """view_draw's camera comes from the viewport's projection matrix: for Blender's own projection
    of the scene camera (Object.calc_matrix_camera) it is the camera's frustum (field of view, shift,
    clip), perspective and orthographic."""
    from obscura_render import convert, engine

    scene = empty_scene()
    scene.render.resolution_x = 2 * SIZE
    camera = add_camera(scene, lens=35.0, shift_x=0.1)
    camera.data.shift_y = -0.05
    for kind in ("PERSP", "ORTHO"):
        camera.data.type = kind
        depsgraph = bpy.context.evaluated_depsgraph_get()
        width, height = engine.render_size(scene)
        projection = camera.evaluated_get(depsgraph).calc_matrix_camera(depsgraph, x=width, y=height)
        ours = convert.camera_from_projection(projection, 1.0)
        truth = synced_prims(scene)["/Camera"]
        scale = 1.0 if kind == "ORTHO" else value(truth, "focalLength") / ours["focalLength"]
        for name in ("horizontalAperture", "verticalAperture", "horizontalApertureOffset", "verticalApertureOffset"):
            expect(abs(ours[name] * scale - value(truth, name)) <= 1e-4 * max(1.0, abs(value(truth, name))),
                   f"{kind} {name}: {ours[name] * scale} vs {value(truth, name)}")
        near, far = ours["clippingRange"]
        expect(abs(near - 0.1) <= 1e-4 and abs(far - 100.0) <= 1e-2, f"{kind} clip {near}, {far}")


def test_progress_and_cancel():
    """render()'s loop reports its progress per frame and stops when Blender asks (Esc: test_break),
    leaving the Render Result unwritten."""
    from obscura_render import engine

    class Engine:  # the RenderEngine calls render() makes, recorded
        def __init__(self, break_after):
            self.break_after, self.progress, self.results, self.reports = break_after, [], 0, []

        def test_break(self):
            return len(self.progress) >= self.break_after

        def update_progress(self, value):
            self.progress.append(value)

        def update_stats(self, *_):
            pass

        def report(self, kinds, message):
            self.reports.append(message)

        def begin_result(self, *_):
            self.results += 1
            raise AssertionError("a result begun after the cancel")

    scene = empty_scene()
    scene.obscura.taa_frames = 8
    add_camera(scene)
    add_plane("Plane", 1.0, principled("Grey", 0.5))
    cancelled = Engine(break_after=3)
    engine.final_render(cancelled, bpy.context.evaluated_depsgraph_get())
    expect(cancelled.progress == [1 / 9, 2 / 9, 3 / 9], f"progress {cancelled.progress}")
    expect(cancelled.results == 0 and not cancelled.reports, f"{cancelled.results} results, {cancelled.reports}")
    expect_no_plugin_errors()


def test_collection_instances_render_through_an_instancer():
    scene = empty_scene()
    add_camera(scene)
    collection = bpy.data.collections.new("Tile")
    mesh = bpy.data.meshes.new("Tile")
    half = 0.25
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    collection.objects.link(bpy.data.objects.new("Tile", mesh))
    for i, x in enumerate((-0.6, 0.6)):
        instance = link(bpy.data.objects.new(f"Copy{i}", None))
        instance.instance_type, instance.instance_collection = "COLLECTION", collection
        instance.location.x = x
    add_light("SUN", 4.0)
    prims = synced_prims(scene)
    instancers = [p for p in prims.values() if p.type == "instancer"]
    expect(len(instancers) == 2 or (len(instancers) == 1 and len(value(instancers[0], "positions")) == 2),
           f"instancers: {[(path, p.type) for path, p in prims.items()]}")
    depth = render_passes(scene, ("Image", "Depth"))["Depth"][..., 0]
    covered = np.isfinite(depth) & (depth < 1e9)
    side = 2 * half * LENS / (CAMERA_DISTANCE * SENSOR) * SIZE  # pixels per tile side
    expect(abs(covered.sum() - 2 * side * side) <= 4 * side, f"{covered.sum()} px covered, 2 x {side:.1f}^2")
    expect_no_plugin_errors()


def test_vector_pass_from_motion_over_the_shutter():
    """A plane moving 2 units per frame, shutter 0.5 frames: it moves 1 unit while the shutter is
    open, f / (D sensor) x width pixels on the image; Blender's Vector pass holds half of that
    towards the previous frame (XY, negative x) and half towards the next (ZW)."""
    scene = empty_scene()
    add_camera(scene)
    plane = add_plane("Moving", 1.0, principled("Grey", 0.5))
    for frame, x in ((0, -2.0), (2, 2.0)):
        plane.location.x = x
        plane.keyframe_insert("location", index=0, frame=frame)
    for key in plane.animation_data.action.fcurves[0].keyframe_points:
        key.interpolation = "LINEAR"
    scene.frame_set(1)
    scene.render.use_motion_blur, scene.render.motion_blur_shutter = True, 0.5
    add_light("SUN", 4.0)
    vector = render_passes(scene, ("Image", "Vector"))["Vector"]
    moved_px = 1.0 * LENS / (CAMERA_DISTANCE * SENSOR) * SIZE
    centre = vector[SIZE // 2 - 2:SIZE // 2 + 2, SIZE // 2 - 2:SIZE // 2 + 2]
    expect(np.allclose(centre[..., 0], -moved_px / 2, atol=0.05 * moved_px), f"previous x {centre[..., 0].ravel()[:4]}")
    expect(np.allclose(centre[..., 2], moved_px / 2, atol=0.05 * moved_px), f"next x {centre[..., 2].ravel()[:4]}")
    # (W, the next frame's y, does not come through the compositor's colour sockets: alpha is 1.)
    expect(np.allclose(centre[..., 1], 0.0, atol=0.05 * moved_px), f"vertical motion {centre[..., 1].ravel()[:4]}")
    expect_no_plugin_errors()


def main() -> int:
    expect(os.environ.get("OBSCURA_VALIDATION") == "1", "OBSCURA_VALIDATION=1 keeps the validation layer on")
    blender_scene.install_addon(ZIP)
    failed = []
    tests = [(name, fn) for name, fn in globals().items() if name.startswith("test_")]
    for name, fn in tests:
        try:
            fn()
            print(f"PASS {name}")
        except Exception:
            traceback.print_exc()
            print(f"FAIL {name}")
            failed.append(name)
        LOG.records.clear()
    print(f"{len(tests) - len(failed)} of {len(tests)} passed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
