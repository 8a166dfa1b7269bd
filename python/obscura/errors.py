"""Exceptions: one class per ObscuraStatus, each carrying the status and the plugin's message."""

from __future__ import annotations

from ._abi import Status


class ObscuraError(Exception):
    """A failed ABI call: ``status`` is the ObscuraStatus, ``message`` the plugin's ``lastError``."""

    status: Status = Status.INTERNAL

    def __init__(self, message: str, status: Status | None = None):
        super().__init__(message)
        if status is not None:
            self.status = Status(status)
        self.message = message

    def __str__(self) -> str:
        return f"{self.message} ({self.status.name})"


class InvalidArgumentError(ObscuraError, ValueError):
    status = Status.INVALID_ARGUMENT


class UnsupportedVersionError(ObscuraError):
    status = Status.UNSUPPORTED_VERSION


class NotFoundError(ObscuraError, LookupError):
    status = Status.NOT_FOUND


class AlreadyExistsError(ObscuraError):
    status = Status.ALREADY_EXISTS


class UnknownTypeError(ObscuraError):
    status = Status.UNKNOWN_TYPE


class BadPrimDataError(ObscuraError):
    """Some prims were skipped for bad data: the image was still rendered without them, unless the
    skipped prim was the camera or a bound render buffer (then nothing was rendered).

    ``callback_errors`` lists the exceptions the scene delegate's Python callbacks raised during
    the render, as ``(prim path, what was asked, exception)``.
    """

    status = Status.BAD_PRIM_DATA

    def __init__(self, message: str, status: Status | None = None,
                 callback_errors: list[tuple[str, str, BaseException]] | None = None):
        super().__init__(message, status)
        self.callback_errors = callback_errors or []


class DeviceError(ObscuraError):
    status = Status.DEVICE


class ValidationError(ObscuraError):
    status = Status.VALIDATION


class OutOfMemoryError(ObscuraError, MemoryError):
    status = Status.OUT_OF_MEMORY


class InvalidStateError(ObscuraError):
    status = Status.INVALID_STATE


class InternalError(ObscuraError):
    status = Status.INTERNAL


_BY_STATUS = {cls.status: cls for cls in (
    InvalidArgumentError, UnsupportedVersionError, NotFoundError, AlreadyExistsError, UnknownTypeError,
    BadPrimDataError, DeviceError, ValidationError, OutOfMemoryError, InvalidStateError, InternalError)}


def error_for(status: int, message: str) -> ObscuraError:
    """The exception for a status a call returned (an unknown number becomes an InternalError)."""
    try:
        known = Status(status)
    except ValueError:
        return InternalError(f"{message} (unknown status {status})")
    return _BY_STATUS.get(known, InternalError)(message, known)
