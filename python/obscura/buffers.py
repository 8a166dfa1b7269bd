"""Render buffers mapped as numpy arrays.

A mapped buffer is read in place: :attr:`MappedBuffer.array` is a read-only numpy view of the
plugin's memory, no copy. The ABI keeps that memory valid and unchanged until the buffer is
unmapped (render refuses to write a mapped buffer), so the package ties the mapping to the views'
lifetime: every view holds
the mapping (and the native delegate) alive, the buffer is unmapped once the last view is gone, and
:meth:`Delegate.render` refuses to run while a view of a mapped buffer is still alive. A view can
therefore never outlive its memory; :meth:`MappedBuffer.copy` gives an array to keep.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ._abi import Format, ObscuraMappedBuffer

if TYPE_CHECKING:
    from .delegate import Delegate

# Components and numpy element type of each format.
_LAYOUT = {
    Format.FLOAT32_VEC4: (4, "<f4"),
    Format.FLOAT32_VEC3: (3, "<f4"),
    Format.FLOAT32: (1, "<f4"),
    Format.INT32: (1, "<i4"),
    Format.UNORM8_VEC4: (4, "|u1"),
}


class _MappedMemory:
    """The numpy base object of a mapping's views. It keeps ``owner`` (the native delegate) alive,
    and the delegate holds only a weak reference to it, to learn when the last view is gone."""

    __slots__ = ("__array_interface__", "owner", "path", "width", "height", "format", "__weakref__")

    def __init__(self, owner: Any, path: str, mapped: ObscuraMappedBuffer):
        self.owner = owner
        self.path = path
        self.width = int(mapped.width)
        self.height = int(mapped.height)
        self.format = Format(mapped.format)
        components, typestr = _LAYOUT[self.format]
        item = np.dtype(typestr).itemsize
        shape: tuple[int, ...] = (self.height, self.width)
        strides: tuple[int, ...] = (int(mapped.rowStride), components * item)
        if components > 1:
            shape, strides = shape + (components,), strides + (item,)
        self.__array_interface__ = {
            "version": 3,
            "shape": shape,
            "typestr": typestr,
            "strides": strides,
            "data": (mapped.data, True),  # read-only
        }


class MappedBuffer:
    """A render buffer mapped for reading; a context manager that unmaps on exit.

    ``array`` has shape (height, width, components) (or (height, width) for one component), rows
    from the top, dtype float32, int32 or uint8 by the buffer's format.
    """

    def __init__(self, delegate: Delegate, memory: _MappedMemory):
        self._delegate = delegate
        self._memory: _MappedMemory | None = memory
        self.path = memory.path
        self.width = memory.width
        self.height = memory.height
        self.format = memory.format

    @property
    def array(self) -> np.ndarray:
        """The zero-copy, read-only view (see the module's note on its lifetime)."""
        if self._memory is None:
            from .errors import InvalidStateError

            raise InvalidStateError(f"{self.path} was unmapped")
        return np.asarray(self._memory)

    def copy(self) -> np.ndarray:
        """The pixels in an array of their own."""
        return self.array.copy()

    def unmap(self) -> None:
        """Done with this mapping. The buffer is unmapped now, or once the last view of it is gone."""
        if self._memory is not None:
            self._memory = None
            self._delegate._release_mappings()

    def __enter__(self) -> MappedBuffer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.unmap()

    def __repr__(self) -> str:
        state = "mapped" if self._memory is not None else "unmapped"
        return f"<MappedBuffer {self.path} {self.width}x{self.height} {self.format.name} {state}>"
