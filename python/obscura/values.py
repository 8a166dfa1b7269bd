"""Python values to ObscuraValue: numpy arrays and sequences in, memory the ABI can point at out.

The ABI says what an attribute's value looks like (its type and whether it is an array); Python
says it with these rules, so that the common cases need no annotation:

========================================  ==============================================
Python                                    ObscuraValue
========================================  ==============================================
``bool``                                  BOOL
``int``                                   INT (int32)
``float``                                 DOUBLE (the delegate takes it for float too)
``str``                                   TOKEN
:class:`Path` (a ``str``)                 PATH (a relationship target, e.g. material:binding)
``tuple`` of 2, 3 or 4 numbers            FLOAT2/3/4 (a colour, a clipping range); INT2 when
                                          both of two are ``int`` (dimensions)
``tuple`` of 16 numbers                   MATRIX4D (row-major, row vectors, as GfMatrix4d)
``list`` or numpy array, 1-D              an array of INT (integer dtype) or FLOAT (float dtype)
``list`` or numpy array of shape (N, k)   an array of FLOAT2/3/4 for k = 2, 3, 4 (points, normals)
``list`` of ``str`` / :class:`Path`       an array of TOKEN / PATH
:class:`Value`                            exactly what it says
========================================  ==============================================

Arrays are handed to the plugin without a copy when they already are C-contiguous float32 or
int32; anything else is converted once, when the value is set. NaN, Inf and out-of-range indices
are not checked here: the delegate checks every value against its schema and skips the prim with a
message naming it, as it does for any host.
"""

from __future__ import annotations

import ctypes
import numbers
from typing import Any, Sequence

import numpy as np

from ._abi import ObscuraValue, ValueType
from .errors import InvalidArgumentError

_INT32 = np.iinfo(np.int32)
_VECTOR_TYPES = {2: ValueType.FLOAT2, 3: ValueType.FLOAT3, 4: ValueType.FLOAT4}


class Path(str):
    """A prim path given as a value (type PATH), e.g. ``Path("/Looks/Grey")`` for ``material:binding``."""

    __slots__ = ()


class Value:
    """An attribute value in the form the ABI reads: it owns the memory it points at.

    Build one directly to say the type explicitly, e.g. ``Value(ValueType.FLOAT3, [1, 0, 0])``
    for a colour held in a numpy array, or ``Value(ValueType.FLOAT, [0.5, 1.0], is_array=True)``.
    """

    __slots__ = ("type", "is_array", "count", "_data", "_keep", "_pointer")

    def __init__(self, type: ValueType, data: Any, is_array: bool = False):
        self.type = ValueType(type)
        self.is_array = bool(is_array)
        if self.type in (ValueType.TOKEN, ValueType.PATH):
            strings = [data] if isinstance(data, str) else list(data)
            encoded = [s.encode("utf-8") for s in strings]
            pointers = (ctypes.c_char_p * max(len(encoded), 1))(*encoded)
            self.count = len(encoded)
            self._data: np.ndarray | None = None
            self._keep: Any = (encoded, pointers)
            self._pointer = ctypes.cast(pointers, ctypes.c_void_p).value
            return
        dtype, components = _element(self.type)
        array = np.ascontiguousarray(data, dtype=dtype)
        if array.size % components:
            raise InvalidArgumentError(f"{array.size} numbers do not make whole {self.type.name} elements")
        self.count = array.size // components
        if not self.is_array and self.count != 1:
            raise InvalidArgumentError(f"a {self.type.name} value needs {components} numbers, got {array.size}")
        self._data = array
        self._keep = None
        self._pointer = address_of(array) if array.size else None

    @property
    def array(self) -> np.ndarray | None:
        """The numbers the plugin reads (None for tokens and paths)."""
        return self._data

    def fill(self, out: ObscuraValue) -> None:
        """Points ``out`` at this value's memory (valid while this object lives)."""
        out.type = self.type
        out.isArray = 1 if self.is_array else 0
        out.count = self.count
        out.data = self._pointer

    def __repr__(self) -> str:
        shown = self._data if self._data is not None else self._keep[0]
        return f"Value({self.type.name}{'[]' if self.is_array else ''}, {shown!r})"


def _element(value_type: ValueType) -> tuple[type, int]:
    """numpy dtype and numbers per element of a numeric value type."""
    if value_type in (ValueType.BOOL, ValueType.INT):
        return np.int32, 1
    if value_type == ValueType.INT2:
        return np.int32, 2
    if value_type == ValueType.FLOAT:
        return np.float32, 1
    if value_type == ValueType.DOUBLE:
        return np.float64, 1
    if value_type == ValueType.MATRIX4D:
        return np.float64, 16
    if value_type in _VECTOR_TYPES.values():
        return np.float32, value_type - ValueType.FLOAT2 + 2
    raise InvalidArgumentError(f"value type {value_type.name} carries no numbers")


def _int32(values: np.ndarray) -> np.ndarray:
    if values.size and (values.min() < _INT32.min or values.max() > _INT32.max):
        raise InvalidArgumentError("integers outside the int32 range")
    return values.astype(np.int32, copy=False)


def _is_number(x: Any) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, (bool, np.bool_))


def _from_tuple(value: tuple) -> Value:
    if not all(_is_number(x) for x in value):
        raise InvalidArgumentError(f"a tuple value holds numbers only, got {value!r}")
    if len(value) == 16:
        return Value(ValueType.MATRIX4D, value)
    if len(value) == 2 and all(isinstance(x, (int, np.integer)) for x in value):
        return Value(ValueType.INT2, _int32(np.asarray(value)))
    if len(value) not in _VECTOR_TYPES:
        raise InvalidArgumentError(f"a tuple value has 2, 3, 4 or 16 numbers, got {len(value)}")
    return Value(_VECTOR_TYPES[len(value)], value)


def _from_array(value: Any) -> Value:
    if isinstance(value, Sequence) and not isinstance(value, np.ndarray) and value and all(
            isinstance(s, str) for s in value):
        paths = all(isinstance(s, Path) for s in value)
        return Value(ValueType.PATH if paths else ValueType.TOKEN, value, is_array=True)
    try:
        array = np.asarray(value)
    except ValueError as e:  # ragged nested sequences
        raise InvalidArgumentError(f"not an array of numbers: {e}") from None
    kind = array.dtype.kind
    if kind not in "biuf":
        raise InvalidArgumentError(f"dtype {array.dtype} is not a number type (use int32 or float32)")
    if array.ndim == 1:
        if kind == "f":
            return Value(ValueType.FLOAT, array, is_array=True)
        return Value(ValueType.INT, _int32(array), is_array=True)
    if array.ndim == 2 and array.shape[1] in _VECTOR_TYPES:
        # Integer vectors exist only as float vectors in the ABI (points of whole numbers).
        return Value(_VECTOR_TYPES[array.shape[1]], array, is_array=True)
    raise InvalidArgumentError(f"shape {array.shape} is not (N,), (N, 2), (N, 3) or (N, 4)")


def to_value(value: Any) -> Value:
    """The :class:`Value` for a Python value, by the rules of this module's table."""
    if isinstance(value, Value):
        return value
    if isinstance(value, (bool, np.bool_)):
        return Value(ValueType.BOOL, int(value))
    if isinstance(value, (int, np.integer)):
        return Value(ValueType.INT, _int32(np.asarray(value)))
    if isinstance(value, (float, np.floating)):
        return Value(ValueType.DOUBLE, float(value))
    if isinstance(value, Path):
        return Value(ValueType.PATH, str(value))
    if isinstance(value, str):
        return Value(ValueType.TOKEN, value)
    if isinstance(value, tuple):
        return _from_tuple(value)
    if isinstance(value, (list, np.ndarray)):
        return _from_array(value)
    raise InvalidArgumentError(f"cannot pass a value of type {type(value).__name__} to the renderer")


def address_of(array: np.ndarray) -> int:
    """The address of an array's first element. (Not ``array.ctypes.data``: numpy keeps a small
    block alive for every ``.ctypes`` object made, which a render loop would accumulate.)"""
    return array.__array_interface__["data"][0]


def to_matrix(value: Any) -> np.ndarray:
    """A 4x4 transform (16 numbers, or 4 rows of 4; GfMatrix4d convention) as 16 contiguous doubles."""
    m = np.ascontiguousarray(value, dtype=np.float64).reshape(-1)
    if m.size != 16:
        raise InvalidArgumentError(f"a transform has 16 numbers, got {m.size}")
    return m
