"""Obscura for Python: the render delegate plugin through its C ABI, with ctypes and numpy.

    import numpy as np
    import obscura

    with obscura.Renderer() as renderer, renderer.delegate() as d:
        d.insert_prim("camera", "/Camera", focalLength=50.0, transform=camera_matrix)
        d.insert_prim("mesh", "/Plane", points=np.array(...), faceVertexCounts=[4], faceVertexIndices=[0, 1, 2, 3])
        d.insert_prim("renderBuffer", "/Buffers/color", dimensions=(64, 64), format="float32Vec4")
        d.set_render_settings(exposure=1.0)
        d.render_until_converged("/Camera", {"color": "/Buffers/color"})
        image = d.read("/Buffers/color")          # (64, 64, 4) float32, a copy

The plugin is found through plugInfo.json on ``OBSCURA_PLUGINPATH`` (else the installed one), as
every Obscura host finds it. ``docs/PYTHON.md`` describes the package; ``docs/schemas.md`` the prims.
"""

from ._abi import ABI_VERSION_MAJOR, ABI_VERSION_MINOR, Dirty, Format, Interpolation, LogLevel, Status, ValueType
from .buffers import MappedBuffer
from .delegate import Delegate, RenderStats
from .discovery import PluginInfo, discover_plugins
from .errors import (
    AlreadyExistsError,
    BadPrimDataError,
    DeviceError,
    InternalError,
    InvalidArgumentError,
    InvalidStateError,
    NotFoundError,
    ObscuraError,
    OutOfMemoryError,
    UnknownTypeError,
    UnsupportedVersionError,
    ValidationError,
)
from .renderer import DeviceInfo, Renderer
from .scene import Scene, SceneDelegate
from .values import Path, Value

__all__ = [
    "ABI_VERSION_MAJOR", "ABI_VERSION_MINOR", "AlreadyExistsError", "BadPrimDataError", "Delegate", "DeviceError",
    "DeviceInfo", "Dirty", "Format", "InternalError", "Interpolation", "InvalidArgumentError", "InvalidStateError",
    "LogLevel", "MappedBuffer", "NotFoundError", "ObscuraError", "OutOfMemoryError", "Path", "PluginInfo",
    "RenderStats", "Renderer", "Scene", "SceneDelegate", "Status", "UnknownTypeError", "UnsupportedVersionError",
    "ValidationError", "Value", "ValueType", "discover_plugins",
]
__version__ = "0.1.0"
