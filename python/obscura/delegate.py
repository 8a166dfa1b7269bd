"""The render delegate: prims in, images out."""

from __future__ import annotations

import collections
import ctypes
import dataclasses
import logging
import threading
import traceback
import weakref
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy as np

from . import _abi
from ._abi import Dirty, LogLevel, Status
from .buffers import MappedBuffer, _MappedMemory
from .errors import BadPrimDataError, InvalidStateError, error_for
from .scene import Scene, SceneDelegate
from .values import Value, address_of, to_matrix, to_value

if TYPE_CHECKING:
    from .renderer import Renderer

_PYTHON_LEVELS = {LogLevel.DEBUG: logging.DEBUG, LogLevel.INFO: logging.INFO, LogLevel.WARNING: logging.WARNING,
                  LogLevel.ERROR: logging.ERROR}
# Messages a delegate keeps for inspection (the logger gets them all).
_KEPT_MESSAGES = 1000


def keyword_name(keyword: str) -> str:
    """``taa_frames`` -> ``taa:frames``: keyword arguments spell USD's namespace colons as underscores
    (no setting or schema attribute name holds an underscore; pass a dict for names that do)."""
    return keyword.replace("_", ":")


@dataclasses.dataclass(frozen=True)
class RenderStats:
    """ObscuraRenderStats: counters of the last render."""

    prims_synced: int
    prims_skipped: int
    validation_errors: int
    converged: bool
    triangles_drawn: int
    device_name: str
    sync_milliseconds: float
    frame_setup_milliseconds: float
    geometry_bytes: int


class _Log:
    """Receives the plugin's log: forwards to a Python logger and keeps the latest messages."""

    def __init__(self, logger: logging.Logger):
        self.logger = logger
        self.errors: collections.deque[str] = collections.deque(maxlen=_KEPT_MESSAGES)
        self.warnings: collections.deque[str] = collections.deque(maxlen=_KEPT_MESSAGES)

    def __call__(self, _user: int, level: int, message: bytes) -> None:
        try:
            text = message.decode("utf-8", "replace")
            if level == LogLevel.ERROR:
                self.errors.append(text)
            elif level == LogLevel.WARNING:
                self.warnings.append(text)
            self.logger.log(_PYTHON_LEVELS.get(LogLevel(level), logging.ERROR), "%s", text)
        except BaseException:  # nothing may unwind into the plugin
            pass


class _Callbacks:
    """The C side of a Python SceneDelegate. Every thunk catches everything: an exception becomes a
    failed status (the delegate then skips that prim and names it), never an unwind through C."""

    def __init__(self, scene: SceneDelegate, logger: logging.Logger):
        self.scene = scene
        self.logger = logger
        self.errors: list[tuple[str, str, BaseException]] = []
        self.held: Value | None = None  # the last value handed out: valid until the next callback

    def _failed(self, path: bytes, what: str, error: BaseException) -> int:
        prim = path.decode("utf-8", "replace")
        self.logger.error("%s: the scene delegate's %s raised %s: %s", prim, what, type(error).__name__, error,
                          exc_info=(type(error), error, error.__traceback__))
        # Kept without its frames: they lead back to the render call's, and through these callbacks
        # (which live as long as the plugin's delegate) would keep the delegate from ever being
        # destroyed. The traceback stays readable as a note.
        error.add_note("".join(traceback.format_tb(error.__traceback__)).rstrip())
        error.__traceback__ = None
        self.errors.append((prim, what, error))
        return Status.BAD_PRIM_DATA

    def get_value(self, _user: int, path: bytes, attribute: bytes, time: float, out: Any) -> int:
        try:
            value = self.scene.get_value(path.decode(), attribute.decode(), time)
            if value is None:
                return Status.NOT_FOUND
            self.held = to_value(value)
            self.held.fill(out.contents)
            return Status.OK
        except BaseException as e:
            return self._failed(path, f"get_value({attribute.decode(errors='replace')!r})", e)

    def get_interpolation(self, _user: int, path: bytes, attribute: bytes, out: Any) -> int:
        try:
            interpolation = self.scene.get_interpolation(path.decode(), attribute.decode())
            if interpolation is None:
                return Status.NOT_FOUND
            out[0] = _abi.Interpolation(interpolation)
            return Status.OK
        except BaseException as e:
            return self._failed(path, f"get_interpolation({attribute.decode(errors='replace')!r})", e)

    def sample_transform(self, _user: int, path: bytes, time0: float, time1: float, max_samples: int,
                         times: Any, matrices: Any, count: Any) -> int:
        try:
            samples = self.scene.sample_transform(path.decode(), time0, time1, max_samples)
            if samples is None:
                return Status.NOT_FOUND  # the identity
            if isinstance(samples, np.ndarray):
                samples = [(time0, samples)]
            samples = list(samples)
            if len(samples) > max_samples:
                raise ValueError(f"{len(samples)} transform samples, at most {max_samples} asked for")
            for i, (t, m) in enumerate(samples):
                times[i] = float(t)
                ctypes.memmove(ctypes.addressof(matrices.contents) + i * 128, address_of(to_matrix(m)), 128)
            count[0] = len(samples)
            return Status.OK
        except BaseException as e:
            return self._failed(path, "sample_transform", e)

    def struct(self) -> tuple[_abi.ObscuraSceneDelegate, tuple]:
        thunks = (_abi.PFN_obscuraGetValue(self.get_value), _abi.PFN_obscuraGetInterpolation(self.get_interpolation),
                  _abi.PFN_obscuraSampleTransform(self.sample_transform))
        sd = _abi.ObscuraSceneDelegate.new(
            flags=0, userData=None,  # not OBSCURA_SCENE_DELEGATE_THREAD_SAFE: see SceneDelegate
            getValue=thunks[0], getInterpolation=thunks[1], sampleTransform=thunks[2])
        return sd, thunks


def _destroy(api: _abi.ObscuraApiV1, handle: int, _keep: tuple) -> None:
    # `_keep` holds the library and the callbacks alive until the plugin is done with them.
    api.destroyDelegate(handle)


class _Native:
    """Owns the plugin's delegate handle: destroyed when this object goes, which is when the
    Delegate is closed (or collected) and no numpy view of its render buffers is left."""

    def __init__(self, api: _abi.ObscuraApiV1, handle: int, keep: tuple):
        self.api = api
        self.handle = handle
        self._finalizer = weakref.finalize(self, _destroy, api, handle, keep)


class Delegate:
    """A render delegate of the plugin (it owns a Vulkan device), with a scene delegate in Python.

    Use it as a context manager, or call :meth:`close`; every call after close raises
    :class:`InvalidStateError`. ``scene`` serves prim data to the plugin: by default an in-memory
    :class:`Scene` that :meth:`insert_prim` fills; pass your own :class:`SceneDelegate` to serve
    values from callbacks instead. The plugin's log goes to ``logger`` (default ``obscura``).
    """

    def __init__(self, renderer: Renderer | None = None, scene: SceneDelegate | None = None, *,
                 device: str | int | None = None, validation: bool | None = None,
                 logger: logging.Logger | None = None):
        if renderer is None:
            from .renderer import Renderer

            renderer = Renderer()
        self.renderer = renderer
        self.scene = Scene() if scene is None else scene
        self.logger = logger or logging.getLogger("obscura")
        self._lock = threading.RLock()
        self._rendering = False
        self._mappings: dict[str, weakref.ref[_MappedMemory]] = {}
        self._log = _Log(self.logger)
        self._callbacks = _Callbacks(self.scene, self.logger)
        api = renderer._api
        log_thunk = _abi.PFN_obscuraLog(self._log)
        info = _abi.ObscuraDelegateCreateInfo.new(
            device=None if device is None else str(device).encode("utf-8"),
            validation=-1 if validation is None else int(bool(validation)),
            log=log_thunk, logUserData=None)
        handle = _abi.ObscuraDelegate()
        status = api.createDelegate(ctypes.byref(info), ctypes.byref(handle))
        if status != Status.OK:
            raise error_for(status, api.lastError(None).decode("utf-8", "replace"))
        scene_struct, thunks = self._callbacks.struct()
        self._native: _Native | None = _Native(api, handle.value, (renderer._library, log_thunk, thunks, self._log,
                                                                   self._callbacks))
        self._check(api.setSceneDelegate(handle, ctypes.byref(scene_struct)))
        renderer._adopt(self)

    # --- lifetime ---------------------------------------------------------------------------

    def close(self) -> None:
        """Destroys the delegate (deferred while numpy views of its buffers are alive). Idempotent."""
        with self._lock:
            self._mappings.clear()
            self._native = None

    @property
    def closed(self) -> bool:
        return self._native is None

    def __enter__(self) -> Delegate:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _open(self) -> _Native:
        """The native delegate, after the checks every call makes."""
        if self._native is None:
            raise InvalidStateError("the delegate is closed")
        if self._rendering:
            raise InvalidStateError("a scene delegate callback called into the delegate that is rendering")
        return self._native

    def _check(self, status: int) -> None:
        if status != Status.OK:
            native = self._native
            message = native.api.lastError(native.handle) if native else b""
            raise error_for(status, message.decode("utf-8", "replace"))

    # --- prims ------------------------------------------------------------------------------

    def insert_prim(self, type: str, path: str, attributes: Mapping[str, Any] | None = None, *,
                    transform: Any = None, interpolations: Mapping[str, _abi.Interpolation] | None = None,
                    **keyword_attributes: Any) -> None:
        """Inserts a prim of ``type`` ("mesh", "camera", "distantLight", "renderBuffer", ...) at ``path``.

        With the default :class:`Scene`, its values are given here: ``attributes`` by their USD
        names, and keyword arguments as :func:`keyword_name` spells them (``points=...``,
        ``inputs_intensity=3.0``); values as :mod:`obscura.values` converts them. ``transform`` is
        the prim's world matrix (GfMatrix4d convention). A custom scene delegate serves its own values.
        """
        with self._lock:
            native = self._open()
            values = dict(attributes or {})
            values.update({keyword_name(k): v for k, v in keyword_attributes.items()})
            prim = None
            if isinstance(self.scene, Scene):
                prim = self.scene.make_prim(type, path, values, transform, interpolations)
            elif values or transform is not None or interpolations:
                raise InvalidStateError(f"{path}: values go to the scene delegate {self.scene!r}, not to insert_prim")
            self._check(native.api.insertPrim(native.handle, type.encode("utf-8"), path.encode("utf-8")))
            if prim is not None:  # only now: a refused insert leaves a prim already at `path` as it was
                self.scene.prims[path] = prim

    def remove_prim(self, path: str) -> None:
        with self._lock:
            native = self._open()
            self._refuse_if_mapped([path])
            self._check(native.api.removePrim(native.handle, path.encode("utf-8")))
            if isinstance(self.scene, Scene):
                self.scene.remove(path)

    def mark_dirty(self, path: str, bits: Dirty | int = Dirty.ALL) -> None:
        """Tells the plugin what changed on a prim (a custom scene delegate calls this after a change)."""
        with self._lock:
            native = self._open()
            self._refuse_if_mapped([path])
            self._check(native.api.markDirty(native.handle, path.encode("utf-8"), int(bits) & 0xFFFFFFFF))

    def set(self, path: str, attribute: str, value: Any, dirty: Dirty | int = Dirty.ALL) -> None:
        """Sets an attribute of a prim of the in-memory :class:`Scene` (None removes it) and marks it dirty."""
        with self._lock:
            self._open()
            self._in_memory_scene().set(path, attribute, value)
            self.mark_dirty(path, dirty)

    def set_transform(self, path: str, transform: Any) -> None:
        with self._lock:
            self._open()
            self._in_memory_scene().set_transform(path, transform)
            self.mark_dirty(path, Dirty.TRANSFORM)

    def _in_memory_scene(self) -> Scene:
        if not isinstance(self.scene, Scene):
            raise InvalidStateError(f"the scene delegate {self.scene!r} holds its own values: change them there "
                                    "and call mark_dirty")
        return self.scene

    def prim_id(self, path: str) -> int:
        """What the primId AOV holds for the mesh at ``path``."""
        with self._lock:
            native = self._open()
            out = ctypes.c_int32()
            self._check(native.api.getPrimId(native.handle, path.encode("utf-8"), ctypes.byref(out)))
            return out.value

    # --- render settings ----------------------------------------------------------------------

    def set_render_settings(self, settings: Mapping[str, Any] | None = None, /, **keyword_settings: Any) -> None:
        """Sets render settings: ``d.set_render_settings(exposure=1.0, taa_frames=8)`` or with a dict
        of exact names (``{"taa:frames": 8}``). bool, int, float and str values; None resets a
        setting to its default. :meth:`Renderer.render_settings` lists them."""
        with self._lock:
            native = self._open()
            merged = dict(settings or {})
            merged.update({keyword_name(k): v for k, v in keyword_settings.items()})
            for name, value in merged.items():
                held = None if value is None else to_value(value)
                c_value = None
                if held is not None:
                    c_value = _abi.ObscuraValue()
                    held.fill(c_value)
                status = native.api.setRenderSetting(native.handle, name.encode("utf-8"),
                                                     ctypes.byref(c_value) if c_value is not None else None)
                self._check(status)

    # --- rendering ----------------------------------------------------------------------------

    def render(self, camera: str, aovs: Mapping[str, str], *, time: float = 0.0,
               viewport: Sequence[int] | None = None, check: bool = True) -> Status:
        """Syncs dirty prims at ``time`` and renders ``camera`` into the render buffers of ``aovs``
        (AOV name -> render buffer path, e.g. ``{"color": "/Buffers/color"}``).

        Returns :attr:`Status.OK`. When prims were skipped for bad data (the image is rendered
        without them) it raises :class:`BadPrimDataError`, or with ``check=False`` returns
        :attr:`Status.BAD_PRIM_DATA`. Exceptions raised by scene-delegate callbacks are in the
        error's ``callback_errors`` (and in :attr:`callback_errors`).
        """
        with self._lock:
            native = self._open()
            api, handle = native.api, native.handle
            del native  # a callback's frame leads back to this one: it must not hold the delegate alive
            self._refuse_if_mapped(list(self._mappings))
            bindings = (_abi.ObscuraAovBinding * max(len(aovs), 1))(
                *[_abi.ObscuraAovBinding(a.encode("utf-8"), b.encode("utf-8")) for a, b in aovs.items()])
            desc = _abi.ObscuraRenderPassDesc.new(cameraPath=camera.encode("utf-8"), time=float(time),
                                                  aovBindingCount=len(aovs), aovBindings=bindings)
            if viewport is not None:
                desc.viewport[:] = [int(v) for v in viewport]
            self._callbacks.errors = []
            self._rendering = True
            try:
                status = api.render(handle, ctypes.byref(desc))
            finally:
                self._rendering = False
                self._callbacks.held = None
            return self._render_result(api, handle, status, check)

    def _render_result(self, api: _abi.ObscuraApiV1, handle: int, status: int, check: bool) -> Status:
        raised = self._callbacks.errors
        for _, _, error in raised:
            if not isinstance(error, Exception):  # KeyboardInterrupt, SystemExit: the user's, re-raised
                raise error
        if status == Status.OK:
            return Status.OK
        message = api.lastError(handle).decode("utf-8", "replace")
        if raised:
            message += "; the scene delegate raised: " + "; ".join(
                f"{prim}: {what}: {type(e).__name__}: {e}" for prim, what, e in raised)
        if status == Status.BAD_PRIM_DATA and not check:
            return Status.BAD_PRIM_DATA
        error = error_for(status, message)
        if isinstance(error, BadPrimDataError):
            error.callback_errors = list(raised)
        raise error from (raised[0][2] if raised else None)

    def render_until_converged(self, camera: str, aovs: Mapping[str, str], *, time: float = 0.0,
                               viewport: Sequence[int] | None = None, check: bool = True,
                               limit: int = 4096) -> int:
        """Renders until :attr:`converged` (temporal AA's ``taa:frames`` frames and the final one);
        returns the number of renders. ``limit`` only guards against a plugin that never converges."""
        for count in range(1, limit + 1):
            self.render(camera, aovs, time=time, viewport=viewport, check=check)
            if self.converged:
                return count
        raise InvalidStateError(f"not converged after {limit} renders")

    @property
    def callback_errors(self) -> list[tuple[str, str, BaseException]]:
        """Exceptions the scene delegate raised during the last render: (prim path, what, exception);
        each holds its traceback as a note rather than its frames."""
        return list(self._callbacks.errors)

    @property
    def logged_errors(self) -> list[str]:
        """The latest error messages of the plugin's log (all of them went to the logger)."""
        return list(self._log.errors)

    @property
    def logged_warnings(self) -> list[str]:
        return list(self._log.warnings)

    @property
    def stats(self) -> RenderStats:
        with self._lock:
            native = self._open()
            s = _abi.ObscuraRenderStats.new()
            self._check(native.api.getRenderStats(native.handle, ctypes.byref(s)))
            return RenderStats(s.primsSynced, s.primsSkipped, s.validationErrors, bool(s.converged),
                               s.trianglesDrawn, s.deviceName.decode("utf-8", "replace"), s.syncMilliseconds,
                               s.frameSetupMilliseconds, s.geometryBytes)

    @property
    def converged(self) -> bool:
        """True when another render of the unchanged scene would add nothing (Hydra's IsConverged)."""
        return self.stats.converged

    @property
    def pass_timings(self) -> dict[str, float]:
        """GPU milliseconds per pass of the last render."""
        with self._lock:
            native = self._open()
            count = ctypes.c_uint32()
            self._check(native.api.getPassTimings(native.handle, None, ctypes.byref(count)))
            timings = (_abi.ObscuraPassTiming * max(count.value, 1))()
            for t in timings:
                t.sType, t.structSize = _abi.StructureType.PASS_TIMING, ctypes.sizeof(_abi.ObscuraPassTiming)
            self._check(native.api.getPassTimings(native.handle, timings, ctypes.byref(count)))
            return {t.pass_.decode("utf-8", "replace"): t.milliseconds for t in timings[:count.value]}

    # --- render buffers -----------------------------------------------------------------------

    def map(self, path: str) -> MappedBuffer:
        """Maps a rendered buffer for reading without a copy (see :mod:`obscura.buffers`)."""
        with self._lock:
            native = self._open()
            self._release_mappings()
            memory = self._mappings[path]() if path in self._mappings else None
            if memory is None:
                mapped = _abi.ObscuraMappedBuffer.new()
                self._check(native.api.mapRenderBuffer(native.handle, path.encode("utf-8"), ctypes.byref(mapped)))
                memory = _MappedMemory(native, path, mapped)
                self._mappings[path] = weakref.ref(memory)
            return MappedBuffer(self, memory)

    def read(self, path: str) -> np.ndarray:
        """A copy of a rendered buffer (mapped, copied, unmapped)."""
        with self.map(path) as mapped:
            return mapped.copy()

    def _release_mappings(self) -> None:
        """Unmaps the buffers whose every view is gone."""
        with self._lock:
            native = self._native
            if native is None or self._rendering:  # closed: nothing to unmap; rendering: later
                return
            for path, memory in list(self._mappings.items()):
                if memory() is None:
                    del self._mappings[path]
                    self._check(native.api.unmapRenderBuffer(native.handle, path.encode("utf-8")))

    def _refuse_if_mapped(self, paths: list[str]) -> None:
        self._release_mappings()
        alive = [p for p in paths if p in self._mappings]
        if alive:
            raise InvalidStateError(
                f"{', '.join(alive)} still mapped: numpy views of it are alive (copy() what you keep, then delete "
                "the views and the MappedBuffer)")

    def __repr__(self) -> str:
        return f"<obscura.Delegate {'closed' if self.closed else 'open'} of {self.renderer.info.library}>"
