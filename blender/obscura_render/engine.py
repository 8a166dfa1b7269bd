"""What stands behind the RenderEngine: the plugin, a Stage (one delegate and the scene synced
into it), the final render and the viewport (Cycles' add-on layout: __init__.py hands over here)."""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import math

import numpy as np

from . import convert, locate

logger = logging.getLogger("obscura_render")

# AOV -> (render buffer format, Blender pass, its channels and channel ids, pass type).
# Blender's passes (RenderEngine.register_pass): Depth is the distance along the view axis,
# Normal world-space, IndexOB the object's pass index, Vector the motion in pixels.
PASSES = {
    "depth": ("float32", "Depth", 1, "Z", "VALUE", "use_pass_z"),
    "normal": ("float32Vec3", "Normal", 3, "XYZ", "VECTOR", "use_pass_normal"),
    "primId": ("int32", "IndexOB", 1, "X", "VALUE", "use_pass_object_index"),
    "motion": ("float32Vec3", "Vector", 4, "XYZW", "VECTOR", "use_pass_vector"),
}


@dataclasses.dataclass
class PluginStatus:
    library: str = ""
    error: str = ""


_renderer = None
_status = PluginStatus()


def plugin_status() -> PluginStatus:
    return _status


def renderer():
    """The process's one obscura.Renderer (the plugin is loaded once); raises locate.PluginMissing,
    and keeps the message for the panel."""
    global _renderer
    if _renderer is None:
        try:
            _renderer = locate.load_renderer()
        except locate.PluginMissing as e:
            _status.error = str(e)
            logger.error("%s", e)
            raise
        _status.error, _status.library = "", str(_renderer.info.library)
    return _renderer


@contextlib.contextmanager
def reported(engine):
    """Nothing raises into Blender: a failure is reported (status bar, console) and logged."""
    try:
        yield
    except locate.PluginMissing as e:
        engine.report({"ERROR"}, str(e))
    except Exception as e:  # the plugin's errors, bad scene data the translation did not expect
        logger.exception("Obscura failed")
        engine.report({"ERROR"}, f"Obscura: {type(e).__name__}: {e}")


def requested_passes(view_layer) -> list[str]:
    return [aov for aov, spec in PASSES.items() if getattr(view_layer, spec[5])]


def register_passes(engine, scene, view_layer) -> None:
    """RenderEngine.update_render_passes: the passes the view layer asks for."""
    engine.register_pass(scene, view_layer, "Combined", 4, "RGBA", "COLOR")
    for aov in requested_passes(view_layer):
        _, name, channels, chan_id, kind, _ = PASSES[aov]
        engine.register_pass(scene, view_layer, name, channels, chan_id, kind)


class Stage:
    """One delegate and the Blender scene synced into it."""

    def __init__(self):
        plugin = renderer()
        from .sync import SceneSync, ShutterScene  # import the obscura package, which renderer() located

        self.delegate = plugin.delegate(ShutterScene(), logger=logging.getLogger("obscura_render.plugin"))
        self.sync = SceneSync(self.delegate, logger)
        self.size: tuple[int, int] | None = None
        self.aovs: dict[str, str] = {}

    def close(self) -> None:
        self.delegate.close()

    def set_buffers(self, width: int, height: int, aovs: list[str]) -> None:
        if self.size == (width, height) and list(self.aovs) == aovs:
            return
        for path in self.aovs.values():
            self.delegate.remove_prim(path)
        self.aovs = {}
        for aov in aovs:
            fmt = "float32Vec4" if aov == "color" else PASSES[aov][0]
            path = f"/Buffers/{aov}"
            self.delegate.insert_prim("renderBuffer", path, dimensions=(width, height), format=fmt)
            self.aovs[aov] = path
        self.size = (width, height)

    def apply_settings(self, scene) -> None:
        self.delegate.set_render_settings(scene.obscura.values())

    def render(self, time: float) -> None:
        """One render; prims with bad data are skipped by the plugin, which logs why."""
        self.delegate.render(convert.CAMERA_PATH, self.aovs, time=time, check=False)

    def read(self, aov: str) -> np.ndarray:
        """The AOV with Blender's row order (bottom row first)."""
        return np.ascontiguousarray(self.delegate.read(self.aovs[aov])[::-1])

    def report_warnings(self, engine) -> None:
        for message in self.sync.warnings:
            engine.report({"WARNING"}, message)
        self.sync.warnings.clear()


def render_size(scene) -> tuple[int, int]:
    scale = scene.render.resolution_percentage / 100.0
    return max(int(scene.render.resolution_x * scale), 1), max(int(scene.render.resolution_y * scale), 1)


def final_render(engine, depsgraph) -> None:
    """RenderEngine.render: every requested pass of the view layer into the Render Result."""
    stage = Stage()
    try:
        _final_render(engine, depsgraph, stage)
    finally:
        stage.close()


def _final_render(engine, depsgraph, stage: Stage) -> None:
    scene, view_layer = depsgraph.scene, depsgraph.view_layer
    width, height = render_size(scene)
    stage.apply_settings(scene)
    engine.update_stats("Obscura", "Syncing the scene")
    stage.sync.sync(depsgraph, width, height)
    stage.report_warnings(engine)
    if scene.camera is None:
        engine.report({"ERROR"}, "the scene has no camera")
        return
    if scene.render.use_motion_blur and scene.render.motion_blur_shutter > 0.0:
        sample_shutter(engine, depsgraph, stage, scene.render.motion_blur_shutter)
    aovs = ["color"] + requested_passes(view_layer)
    stage.set_buffers(width, height, aovs)
    frames = scene.obscura.taa_frames if scene.obscura.taa else 1
    for i in range(frames + 1):  # taa:frames accumulated, then the final (converged) render
        if engine.test_break():
            return
        stage.render(float(scene.frame_current))
        engine.update_progress(min((i + 1) / (frames + 1), 1.0))
        engine.update_stats("Obscura", f"Frame {i + 1} of {frames + 1}")
        if stage.delegate.converged:
            break
    for message in stage.delegate.logged_errors:
        engine.report({"ERROR"}, message)
    result = engine.begin_result(0, 0, width, height)
    layer = result.layers[0]
    layer.passes["Combined"].rect = stage.read("color").reshape(-1, 4)
    camera = stage.sync.camera_values(depsgraph, width, height)[0]
    for aov in aovs[1:]:
        layer.passes[PASSES[aov][1]].rect = blender_pass(stage, aov, camera).reshape(width * height, -1)
    engine.end_result(result)


def sample_shutter(engine, depsgraph, stage: Stage, shutter: float) -> None:
    """Motion blur over Blender's shutter (Render > Motion Blur > Shutter, in frames, centred on the
    frame as Cycles' default position): every object's and the camera's transform at the shutter's
    open, the frame and its close (RenderEngine.frame_set evaluates the depsgraph there), and the
    camera's shutter:open/close. Instances and deforming meshes are sampled at the frame only."""
    frame = depsgraph.scene.frame_current
    samples: dict[str, list] = {}
    for offset in (-shutter / 2.0, 0.0, shutter / 2.0):
        whole = math.floor(frame + offset)
        engine.frame_set(int(whole), frame + offset - whole)
        for path, matrix in stage.sync.world_matrices(depsgraph).items():
            samples.setdefault(path, []).append((frame + offset, matrix))
    engine.frame_set(frame, 0.0)
    stage.delegate.scene.samples = samples
    stage.delegate.set(convert.CAMERA_PATH, "shutter:open", -shutter / 2.0)
    stage.delegate.set(convert.CAMERA_PATH, "shutter:close", shutter / 2.0)


def blender_pass(stage: Stage, aov: str, camera: dict) -> np.ndarray:
    """An Obscura AOV as the Blender pass of the same meaning."""
    data = stage.read(aov)
    if aov == "depth":
        near, far = camera["clippingRange"]
        return convert.linear_depth(data, near, far, camera["projection"] == "orthographic")
    if aov == "normal":
        # Eye space (Hydra's Neye) to world space: rows of the camera's GfMatrix4d are its axes.
        camera_prim = stage.delegate.scene.prims[convert.CAMERA_PATH]
        rotation = np.asarray(camera_prim.transform, np.float64).reshape(4, 4)[:3, :3]
        return (data.reshape(-1, 3) @ rotation).astype(np.float32)
    if aov == "primId":
        ids = {stage.delegate.prim_id(p): i for p, i in stage.sync.pass_index.items()}
        table = np.zeros(max(ids, default=0) + 2, np.float32)  # index 0 holds -1: nothing drawn
        for prim_id, index in ids.items():
            table[prim_id + 1] = index
        return table[np.clip(data.astype(np.int64) + 1, 0, len(table) - 1)]
    # motion: pixels x right, y down over the shutter; Blender's Vector holds the motion towards
    # the previous frame (XY) and the next (ZW), y up.
    x, y = data[..., 0], -data[..., 1]
    return np.stack([-x / 2, -y / 2, x / 2, y / 2], axis=-1).astype(np.float32)


# --- viewport ---------------------------------------------------------------------------------

class Viewport:
    """A viewport's stage: synced once, then updated from depsgraph updates; drawn progressively."""

    def __init__(self):
        self.stage = Stage()
        self.synced = False
        self.last_camera = None

    def update(self, engine, depsgraph, width: int, height: int) -> int:
        """RenderEngine.view_update: the whole scene the first time, then only what changed."""
        stage = self.stage
        if not self.synced:
            stage.apply_settings(depsgraph.scene)
            stage.sync.sync(depsgraph, width, height)
            self.synced = True
            dirtied = len(stage.delegate.scene.prims)
        else:
            stage.apply_settings(depsgraph.scene)
            dirtied = stage.sync.update(depsgraph)
        stage.report_warnings(engine)
        return dirtied

    def draw(self, engine, context, depsgraph) -> None:
        """RenderEngine.view_draw: follow the viewport's camera, render once, draw the colour AOV."""
        import gpu
        from gpu_extras.presets import draw_texture_2d

        region, view = context.region, context.region_data
        width, height = region.width, region.height
        stage = self.stage
        stage.set_buffers(width, height, ["color"])
        mpu = stage.sync.meters_per_unit(depsgraph.scene)
        camera = convert.camera_from_projection(view.window_matrix, mpu)
        transform = convert.usd_matrix(view.view_matrix.inverted())
        key = (tuple(sorted(camera.items())), tuple(transform))
        if key != self.last_camera:  # the camera moved: a changed camera restarts accumulation
            stage.sync.put("camera", convert.CAMERA_PATH, camera, transform)
            self.last_camera = key
        stage.render(float(depsgraph.scene.frame_current))
        pixels = stage.read("color")
        buffer = gpu.types.Buffer("FLOAT", width * height * 4, pixels.ravel())
        texture = gpu.types.GPUTexture((width, height), format="RGBA16F", data=buffer)
        gpu.state.blend_set("ALPHA_PREMULT")
        engine.bind_display_space_shader(depsgraph.scene)
        draw_texture_2d(texture, (0, 0), width, height)
        engine.unbind_display_space_shader()
        gpu.state.blend_set("NONE")
        if not stage.delegate.converged:
            engine.tag_redraw()  # temporal AA goes on accumulating while nothing changes
