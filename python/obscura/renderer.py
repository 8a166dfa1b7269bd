"""The renderer plugin: found through plugInfo.json, loaded, its ABI version negotiated."""

from __future__ import annotations

import ctypes
import dataclasses
import weakref
from typing import TYPE_CHECKING, Any

from . import _abi
from ._abi import Status
from .discovery import PluginInfo, discover_plugins
from .errors import InvalidStateError, NotFoundError, UnsupportedVersionError, error_for

if TYPE_CHECKING:
    from .delegate import Delegate
    from .scene import SceneDelegate


@dataclasses.dataclass(frozen=True)
class DeviceInfo:
    """A Vulkan device the plugin can render with (ObscuraDeviceInfo)."""

    name: str
    driver: str
    api_version: tuple[int, int, int]  #: Vulkan major, minor, patch
    is_discrete: bool
    is_cpu: bool
    max_msaa_samples: int


def _load(info: PluginInfo, major: int, minor: int) -> tuple[ctypes.CDLL, _abi.ObscuraApiV1]:
    """dlopen + obscuraGetApi(major, minor), as the harness's loadPlugin; raises with the reason."""
    try:
        library = ctypes.CDLL(str(info.library), mode=ctypes.RTLD_LOCAL)
    except OSError as e:
        raise NotFoundError(f"{info.library}: {e}") from None
    try:
        get_api = _abi.PFN_obscuraGetApi((_abi.GET_API_SYMBOL, library))
    except AttributeError:
        raise NotFoundError(f"{info.library}: no {_abi.GET_API_SYMBOL} symbol (not an Obscura plugin)") from None
    table = ctypes.c_void_p()
    status = get_api(major, minor, ctypes.byref(table))
    if status != Status.OK or not table.value:
        declared = f" (it declares {info.abi_version})" if info.abi_version else ""
        raise UnsupportedVersionError(f"{info.library}: the plugin does not provide ABI {major}.{minor}{declared}")
    api = ctypes.cast(table, ctypes.POINTER(_abi.ObscuraApiV1)).contents
    if api.structSize < ctypes.sizeof(_abi.ObscuraApiV1) or api.versionMajor != major:
        raise UnsupportedVersionError(
            f"{info.library}: function table of ABI {api.versionMajor}.{api.versionMinor}, {api.structSize} bytes; "
            f"ABI {major}.{minor} needs {ctypes.sizeof(_abi.ObscuraApiV1)}")
    return library, api


class Renderer:
    """The loaded plugin. ``Renderer()`` takes the highest-priority plugin on ``OBSCURA_PLUGINPATH``
    (else the installed one) that provides ABI 1.0; ``plugin`` picks one explicitly.

    A context manager: closing it closes the delegates it made. (The library stays loaded for the
    process's life, as ctypes never unloads one.)
    """

    def __init__(self, search_path: str | None = None, *, plugin: PluginInfo | None = None):
        candidates = [plugin] if plugin else discover_plugins(search_path).plugins
        if not candidates:
            found = discover_plugins(search_path)
            problems = "".join(f"\n  {p}" for p in found.problems)
            raise NotFoundError("no renderer plugin found (searched OBSCURA_PLUGINPATH and the installed plugin "
                                f"folders){problems}")
        reasons = []
        for info in candidates:
            try:
                self._library, self._api = _load(info, _abi.ABI_VERSION_MAJOR, _abi.ABI_VERSION_MINOR)
            except (NotFoundError, UnsupportedVersionError) as e:
                reasons.append(e)
                continue
            self.info = info
            break
        else:
            if len(reasons) == 1:
                raise reasons[0]
            raise UnsupportedVersionError("no plugin could be loaded:" + "".join(f"\n  {r.message}" for r in reasons))
        self._delegates: weakref.WeakSet[Delegate] = weakref.WeakSet()
        self._closed = False

    @property
    def version(self) -> tuple[int, int]:
        """The ABI version of the negotiated function table."""
        return self._api.versionMajor, self._api.versionMinor

    def devices(self) -> list[DeviceInfo]:
        """The Vulkan devices visible to the plugin."""
        count = ctypes.c_uint32()
        self._check(self._api.enumerateDevices(None, ctypes.byref(count)))
        infos = (_abi.ObscuraDeviceInfo * max(count.value, 1))()
        for d in infos:
            d.sType, d.structSize = _abi.StructureType.DEVICE_INFO, ctypes.sizeof(_abi.ObscuraDeviceInfo)
        self._check(self._api.enumerateDevices(infos, ctypes.byref(count)))
        return [DeviceInfo(d.name.decode(), d.driver.decode(),
                           ((d.apiVersion >> 22) & 0x7F, (d.apiVersion >> 12) & 0x3FF, d.apiVersion & 0xFFF),
                           bool(d.isDiscrete), bool(d.isCpu), d.maxMsaaSamples) for d in infos[:count.value]]

    def render_settings(self) -> dict[str, str]:
        """Every render setting the plugin understands, with its description."""
        settings = {}
        name, description = ctypes.c_char_p(), ctypes.c_char_p()
        index = 0
        while self._api.describeRenderSetting(index, ctypes.byref(name), ctypes.byref(description)) == Status.OK:
            settings[name.value.decode()] = description.value.decode()
            index += 1
        return settings

    def delegate(self, scene: SceneDelegate | None = None, **options: Any) -> Delegate:
        """A new :class:`Delegate` (``options``: device, validation, logger)."""
        from .delegate import Delegate

        return Delegate(self, scene, **options)

    def _adopt(self, delegate: Delegate) -> None:
        if self._closed:
            delegate.close()
            raise InvalidStateError("the renderer is closed")
        self._delegates.add(delegate)

    def _check(self, status: int) -> None:
        if status != Status.OK:
            raise error_for(status, self._api.lastError(None).decode("utf-8", "replace"))

    def close(self) -> None:
        """Closes every delegate made from this renderer."""
        self._closed = True
        for delegate in list(self._delegates):
            delegate.close()

    def __enter__(self) -> Renderer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<obscura.Renderer {self.info.display_name} ABI {self.version[0]}.{self.version[1]} {self.info.library}>"
