"""The add-on's viewport in Blender's own UI: Blender runs with a window (under Xvfb, Mesa's GL),
a 3D viewport in Rendered shading draws Obscura's image through the add-on's view_draw, and the
window's pixels are read back (Blender's screenshot operator) once the image has converged.

    blender --factory-startup --python viewport_test.py -- ADDON_ZIP TESTS_PYTHON_DIR WORK_DIR

An emissive square (black base colour, no specular: it shows its emission alone) under a world of
constant colour (the dome, which the camera sees where nothing is drawn), looked at head-on by the
viewport. With the Standard view transform and no dither the window holds sRGB-encoded radiance
(IEC 61966-2-1) in 8 bits: the square's pixels are its emission, the others the world's colour,
each within the renderer's radiance tolerance and half a code value of rounding. The square's
edges lie where the viewport's own projection (RegionView3D.perspective_matrix) puts its corners,
within a pixel: the add-on followed the viewport's camera. view_draw drew more than once,
converged, and asked for no redraw after that. Leaving Rendered shading frees the engine and closes
its delegate; nothing logged an error (validation on: objects left alive are errors).
"""

from __future__ import annotations

import os
import sys
import time
import traceback
from pathlib import Path

import bpy
import numpy as np
from mathutils import Quaternion, Vector

ZIP, TESTS_PYTHON, WORK = sys.argv[sys.argv.index("--") + 1:][:3]
sys.path[:0] = [TESTS_PYTHON, str(Path(__file__).resolve().parent)]
import blender_scene  # noqa: E402
from blender_scene import add_plane, expect, expect_no_plugin_errors, principled  # noqa: E402

EMISSION = (0.6, 0.3, 0.1)  # linear radiance of the square
WORLD = (0.05, 0.1, 0.2)  # linear radiance of the world
HALF = 1.0  # the square's half side, metres
VIEW_DISTANCE = 5.0
TIMEOUT_S = 240.0

# What view_draw did: one entry per call, whether the image had converged after it.
DRAWS: list[bool] = []
VIEWPORTS = []  # the add-on's Viewport objects that drew


def record_draws():
    """Wraps the add-on's Viewport.draw (what its RenderEngine.view_draw calls) to log each call."""
    from obscura_render import engine

    draw = engine.Viewport.draw

    def recorded(self, render_engine, context, depsgraph):
        draw(self, render_engine, context, depsgraph)
        DRAWS.append(bool(self.stage.delegate.converged))
        if self not in VIEWPORTS:
            VIEWPORTS.append(self)

    engine.Viewport.draw = recorded


def build_scene():
    scene = blender_scene.empty_scene(64)  # (F12's size; the viewport renders at its region's)
    scene.world = bpy.data.worlds.new("Sky")
    scene.world.use_nodes = False
    scene.world.color = WORLD
    material = principled("Glow", 0.0)
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Emission"].default_value = (*EMISSION, 1.0)
    bsdf.inputs["Emission Strength"].default_value = 1.0
    add_plane("Square", HALF, material)
    # Display-referred sRGB in the window: no filmic curve, no look, no dither noise.
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure, scene.view_settings.gamma = 0.0, 1.0
    scene.display_settings.display_device = "sRGB"
    scene.render.dither_intensity = 0.0
    return scene


def viewport():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return window, area, region


def look_at_the_square():
    _, area, _ = viewport()
    space = area.spaces.active
    space.overlay.show_overlays = False  # the region shows the engine's image alone
    space.show_gizmo = False
    space.lens, space.clip_start, space.clip_end = 50.0, 0.1, 100.0
    view = space.region_3d
    view.view_perspective = "PERSP"
    view.view_rotation = Quaternion((1.0, 0.0, 0.0, 0.0))  # looking down -Z at the square
    view.view_location = (0.0, 0.0, 0.0)
    view.view_distance = VIEW_DISTANCE
    space.shading.type = "RENDERED"


def srgb_code(linear: float) -> float:
    """IEC 61966-2-1's encoding, in 8-bit code values (unrounded)."""
    v = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return 255.0 * v


def code_range(linear: float, channel: int) -> tuple[float, float]:
    """The code values a radiance may show as: the renderer's tolerance, then half a code value of
    the window's 8-bit rounding."""
    from lit_plane import radiance_tolerance

    tolerance = radiance_tolerance(linear, channel)
    return srgb_code(max(linear - tolerance, 0.0)) - 0.5, srgb_code(linear + tolerance) + 0.5


def screenshot() -> np.ndarray:
    """The window's pixels (8-bit codes), bottom row first as window coordinates are."""
    window, area, _ = viewport()
    path = str(Path(WORK) / "viewport.png")
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.screen.screenshot(filepath=path, check_existing=False)
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return np.round(pixels.reshape(height, width, 4)[..., :3] * 255.0)


def projected_square() -> tuple[float, float, float, float]:
    """The square's extent in the viewport region's pixels (left, right, bottom, top), by the
    viewport's own projection."""
    _, area, region = viewport()
    matrix = area.spaces.active.region_3d.perspective_matrix
    xs, ys = [], []
    for corner in ((-HALF, -HALF), (HALF, HALF)):
        clip = matrix @ Vector((corner[0], corner[1], 0.0, 1.0))
        xs.append((clip.x / clip.w + 1.0) / 2.0 * region.width)
        ys.append((clip.y / clip.w + 1.0) / 2.0 * region.height)
    return xs[0], xs[1], ys[0], ys[1]


def under_the_ui() -> np.ndarray:
    """The viewport region's pixels that Blender's UI covers: the toolbar and headers (regions
    overlapping it), and a band along its edges (the area's border, the sidebar's arrow)."""
    _, area, region = viewport()
    covered = np.ones((region.height, region.width), bool)
    band = 16
    covered[band:-band, band:-band] = False
    for other in area.regions:
        if other.type != "WINDOW" and other.width > 1 and other.height > 1:
            x0, y0 = other.x - region.x, other.y - region.y
            covered[max(y0, 0):max(y0 + other.height, 0), max(x0, 0):max(x0 + other.width, 0)] = True
    return covered


def check_the_window():
    expect(len(DRAWS) >= 2 and DRAWS[-1], f"view_draw calls, converged after each: {DRAWS}")
    _, _, region = viewport()
    pixels = screenshot()[region.y:region.y + region.height, region.x:region.x + region.width]
    left, right, bottom, top = projected_square()
    # Pixel centres at least a pixel inside the square, and at least a pixel outside it.
    x = np.arange(region.width) + 0.5
    y = np.arange(region.height) + 0.5
    def beyond(margin):
        return ((x[None, :] < left - margin) | (x[None, :] > right + margin) | (y[:, None] < bottom - margin) |
                (y[:, None] > top + margin))

    inside = ((x[None, :] > left + 1) & (x[None, :] < right - 1) & (y[:, None] > bottom + 1) & (y[:, None] < top - 1))
    # The delegate's image holds the world's radiance from a pixel beyond the square on. The window
    # shows it through Blender's drawing of the image, which blends about 1% of the row below into
    # the row above the square's top edge (measured: 0.05 shown as code 65 beside an edge row of
    # half coverage, where the image holds 0.04999): the window is held to it from two pixels on.
    image = VIEWPORTS[-1].stage.read("color").reshape(region.height, region.width, 4)
    from lit_plane import radiance_tolerance

    for c in range(3):
        values = image[..., c][beyond(1) & ~under_the_ui()]
        tolerance = radiance_tolerance(WORLD[c], c)
        expect(np.abs(values - WORLD[c]).max() <= tolerance,
               f"world in the image, channel {c}: {values.min()}..{values.max()}, expected {WORLD[c]} +- {tolerance}")
    outside = beyond(2) & ~under_the_ui()
    expect(inside.sum() > 1000 and outside.sum() > 1000, f"{inside.sum()} px inside, {outside.sum()} outside")
    for c in range(3):
        for name, where, radiance in (("square", inside, EMISSION[c]), ("world", outside, WORLD[c])):
            low, high = code_range(radiance, c)
            values = pixels[..., c][where]
            expect(values.min() >= low and values.max() <= high,
                   f"{name}, channel {c}: codes {values.min()}..{values.max()}, expected {low:.2f}..{high:.2f}")
    # The square's edges, where the centre row and column cross from the world to the square.
    row, column = pixels[region.height // 2, :, 1], pixels[:, region.width // 2, 1]
    square_code = srgb_code(EMISSION[1])
    halfway = (square_code + srgb_code(WORLD[1])) / 2.0  # the square is brighter in green
    across = np.flatnonzero(row > halfway)
    up = np.flatnonzero(column > halfway)
    for name, found, expected in (("left", across[0], left), ("right", across[-1] + 1, right),
                                  ("bottom", up[0], bottom), ("top", up[-1] + 1, top)):
        expect(abs(found - expected) <= 1.0, f"{name} edge at {found} px, projected at {expected:.2f}")
    print(f"view_draw: {len(DRAWS)} calls until converged; square {right - left:.1f} x {top - bottom:.1f} px")


def finish():
    """Rendered shading off: Blender frees the viewport's engine and with it the delegate, whose
    validation layer reports any Vulkan object left alive."""
    viewport()[1].spaces.active.shading.type = "SOLID"


class Steps:
    """The test as a timer of Blender's event loop: the window draws between steps."""

    def __init__(self):
        self.start = 0.0
        self.step = self.set_up
        self.settled = 0

    def __call__(self):
        try:
            return self.step()
        except Exception:
            traceback.print_exc()
            print("FAIL viewport")
            sys.stdout.flush()
            os._exit(1)

    def set_up(self):
        self.start = time.monotonic()
        expect(os.environ.get("OBSCURA_VALIDATION") == "1", "OBSCURA_VALIDATION=1 keeps the validation layer on")
        blender_scene.install_addon(ZIP)
        record_draws()
        build_scene()
        look_at_the_square()
        self.step = self.wait_for_convergence
        return 0.5

    def wait_for_convergence(self):
        expect(time.monotonic() - self.start < TIMEOUT_S, f"no converged draw in {TIMEOUT_S} s: {DRAWS}")
        if not DRAWS or not DRAWS[-1]:
            return 0.5
        # Converged: the add-on asks for no more redraws; a second later nothing more was drawn.
        self.settled = len(DRAWS)
        self.step = self.check
        return 1.0

    def check(self):
        expect(len(DRAWS) == self.settled, f"drawn again after converging: {DRAWS}")
        check_the_window()
        finish()
        self.step = self.close
        return 1.0

    def close(self):
        expect(VIEWPORTS and all(v.stage.delegate.closed for v in VIEWPORTS), "the viewport's delegate is open")
        expect_no_plugin_errors()
        print("PASS viewport")
        sys.stdout.flush()
        bpy.ops.wm.quit_blender()
        return None


bpy.context.preferences.view.show_splash = False
# Persistent: the scene is built in a new (empty) file, whose loading would remove the timer.
bpy.app.timers.register(Steps(), first_interval=0.5, persistent=True)
