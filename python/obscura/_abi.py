"""ctypes mirror of the plugin's C ABI, ``include/obscura/obscura.h`` (ABI 1.0).

Every struct, enum and function-pointer type below copies the header field by field, in order;
``tests/python/test_abi_layout.py`` checks sizes and offsets against the C compiler's. Nothing
here is Pythonic: the rest of the package wraps it.
"""

from __future__ import annotations

import ctypes
import enum
from ctypes import (
    CFUNCTYPE,
    POINTER,
    Structure,
    c_char,
    c_char_p,
    c_double,
    c_int,
    c_int32,
    c_size_t,
    c_uint16,
    c_uint32,
    c_uint64,
    c_void_p,
)

ABI_VERSION_MAJOR = 1
ABI_VERSION_MINOR = 3
GET_API_SYMBOL = "obscuraGetApi"


class Status(enum.IntEnum):
    """ObscuraStatus: what every ABI function returns."""

    OK = 0
    INVALID_ARGUMENT = 1
    UNSUPPORTED_VERSION = 2
    NOT_FOUND = 3
    ALREADY_EXISTS = 4
    UNKNOWN_TYPE = 5
    BAD_PRIM_DATA = 6
    DEVICE = 7
    VALIDATION = 8
    OUT_OF_MEMORY = 9
    INVALID_STATE = 10
    INTERNAL = 11


class ValueType(enum.IntEnum):
    """ObscuraValueType: the element type of an ObscuraValue."""

    NONE = 0
    BOOL = 1
    INT = 2
    FLOAT = 3
    DOUBLE = 4
    FLOAT2 = 5
    FLOAT3 = 6
    FLOAT4 = 7
    INT2 = 8
    MATRIX4D = 9
    TOKEN = 10
    PATH = 11


class Interpolation(enum.IntEnum):
    """ObscuraInterpolation of a primvar, as UsdGeomPrimvar's."""

    CONSTANT = 0
    UNIFORM = 1
    VARYING = 2
    VERTEX = 3
    FACE_VARYING = 4


class Dirty(enum.IntFlag):
    """ObscuraDirtyBits: what changed on a prim since its last sync."""

    CLEAN = 0x0000
    TRANSFORM = 0x0001
    POINTS = 0x0002
    TOPOLOGY = 0x0004
    NORMALS = 0x0008
    PRIMVAR = 0x0010
    MATERIAL_ID = 0x0020
    PARAMS = 0x0040
    VISIBILITY = 0x0080
    DOUBLE_SIDED = 0x0100
    ALL = 0xFFFFFFFF


class StructureType(enum.IntEnum):
    DELEGATE_CREATE_INFO = 1
    SCENE_DELEGATE = 2
    RENDER_PASS_DESC = 3
    MAPPED_BUFFER = 4
    DEVICE_INFO = 5
    PASS_TIMING = 6
    RENDER_STATS = 7
    MEMORY_STATS = 8  # ABI 1.1
    EXTERNAL_BUFFER = 9  # ABI 1.2
    INTEROP_STATS = 10  # ABI 1.2
    CULLING_STATS = 11  # ABI 1.3


class LogLevel(enum.IntEnum):
    DEBUG = 0
    INFO = 1
    WARNING = 2
    ERROR = 3


class Format(enum.IntEnum):
    """ObscuraFormat of a mapped render buffer."""

    UNKNOWN = 0
    FLOAT32_VEC4 = 1
    FLOAT32_VEC3 = 2
    FLOAT32 = 3
    INT32 = 4
    UNORM8_VEC4 = 5


SCENE_DELEGATE_THREAD_SAFE = 0x1

# C enums are int-sized on every ABI the plugin is built for (System V x86-64, AArch64).
c_enum = c_int
ObscuraDelegate = c_void_p


class ObscuraValue(Structure):
    _fields_ = [("type", c_enum), ("isArray", c_int32), ("count", c_size_t), ("data", c_void_p)]


PFN_obscuraLog = CFUNCTYPE(None, c_void_p, c_enum, c_char_p)
PFN_obscuraGetValue = CFUNCTYPE(c_enum, c_void_p, c_char_p, c_char_p, c_double, POINTER(ObscuraValue))
PFN_obscuraGetInterpolation = CFUNCTYPE(c_enum, c_void_p, c_char_p, c_char_p, POINTER(c_enum))
PFN_obscuraSampleTransform = CFUNCTYPE(
    c_enum, c_void_p, c_char_p, c_double, c_double, c_uint32, POINTER(c_double), POINTER(c_double), POINTER(c_uint32)
)


class _Extensible(Structure):
    """A struct that starts with sType / pNext / structSize; ``new()`` fills them."""

    _structure_type: StructureType

    @classmethod
    def new(cls, **fields):
        s = cls(**fields)
        s.sType = cls._structure_type
        s.pNext = None
        s.structSize = ctypes.sizeof(cls)
        return s


class ObscuraDelegateCreateInfo(_Extensible):
    _structure_type = StructureType.DELEGATE_CREATE_INFO
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("device", c_char_p),
        ("validation", c_int32),
        ("log", PFN_obscuraLog),
        ("logUserData", c_void_p),
    ]


class ObscuraSceneDelegate(_Extensible):
    _structure_type = StructureType.SCENE_DELEGATE
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("flags", c_uint32),
        ("userData", c_void_p),
        ("getValue", PFN_obscuraGetValue),
        ("getInterpolation", PFN_obscuraGetInterpolation),
        ("sampleTransform", PFN_obscuraSampleTransform),
    ]


class ObscuraAovBinding(Structure):
    _fields_ = [("aov", c_char_p), ("renderBufferPath", c_char_p)]


class ObscuraRenderPassDesc(_Extensible):
    _structure_type = StructureType.RENDER_PASS_DESC
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("cameraPath", c_char_p),
        ("viewport", c_int32 * 4),
        ("time", c_double),
        ("aovBindingCount", c_uint32),
        ("aovBindings", POINTER(ObscuraAovBinding)),
    ]


class ObscuraMappedBuffer(_Extensible):
    _structure_type = StructureType.MAPPED_BUFFER
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("width", c_uint32),
        ("height", c_uint32),
        ("format", c_enum),
        ("rowStride", c_size_t),
        ("data", c_void_p),
    ]


class ObscuraDeviceInfo(_Extensible):
    _structure_type = StructureType.DEVICE_INFO
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("name", c_char * 256),
        ("driver", c_char * 256),
        ("apiVersion", c_uint32),
        ("isDiscrete", c_int32),
        ("isCpu", c_int32),
        ("maxMsaaSamples", c_uint32),
    ]


class ObscuraPassTiming(_Extensible):
    _structure_type = StructureType.PASS_TIMING
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("pass_", c_char * 64),  # `pass` in C; a Python keyword
        ("milliseconds", c_double),
    ]


class ObscuraRenderStats(_Extensible):
    _structure_type = StructureType.RENDER_STATS
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("primsSynced", c_uint32),
        ("primsSkipped", c_uint32),
        ("validationErrors", c_uint32),
        ("converged", c_uint32),
        ("trianglesDrawn", c_uint64),
        ("deviceName", c_char * 256),
        ("syncMilliseconds", c_double),
        ("frameSetupMilliseconds", c_double),
        ("geometryBytes", c_uint64),
    ]


class ObscuraMemoryStats(_Extensible):
    """ABI 1.1, chained to ObscuraRenderStats.pNext: the delegate's Vulkan memory (by kind since 1.3)."""
    _structure_type = StructureType.MEMORY_STATS
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("deviceMemoryBlocks", c_uint32),
        ("deviceMemoryReserved", c_uint64),
        ("deviceMemoryInUse", c_uint64),
        ("imageBytes", c_uint64),
        ("frameTargetBytes", c_uint64),
        ("frameHistoryBytes", c_uint64),
        ("textureBytes", c_uint64),
        ("geometryBytes", c_uint64),
        ("renderBufferBytes", c_uint64),
    ]


class ObscuraCullingStats(_Extensible):
    """ABI 1.3, chained to ObscuraRenderStats.pNext: occlusion culling in the last render's camera view."""
    _structure_type = StructureType.CULLING_STATS
    _fields_ = [
        ("sType", c_enum),
        ("pNext", c_void_p),
        ("structSize", c_uint32),
        ("draws", c_uint32),
        ("drawsCulled", c_uint32),
        ("instances", c_uint64),
        ("instancesCulled", c_uint64),
        ("triangles", c_uint64),
        ("trianglesCulled", c_uint64),
        ("milliseconds", c_double),
        ("drawsOutsideView", c_uint32),
        ("instancesOutsideView", c_uint64),
        ("trianglesOutsideView", c_uint64),
    ]


_D = ObscuraDelegate
_S = c_enum  # every function returns an ObscuraStatus


class ObscuraApiV1(Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("versionMajor", c_uint16),
        ("versionMinor", c_uint16),
        ("createDelegate", CFUNCTYPE(_S, POINTER(ObscuraDelegateCreateInfo), POINTER(_D))),
        ("destroyDelegate", CFUNCTYPE(_S, _D)),
        ("lastError", CFUNCTYPE(c_char_p, _D)),
        ("setSceneDelegate", CFUNCTYPE(_S, _D, POINTER(ObscuraSceneDelegate))),
        ("insertPrim", CFUNCTYPE(_S, _D, c_char_p, c_char_p)),
        ("removePrim", CFUNCTYPE(_S, _D, c_char_p)),
        ("markDirty", CFUNCTYPE(_S, _D, c_char_p, c_uint32)),
        ("setRenderSetting", CFUNCTYPE(_S, _D, c_char_p, POINTER(ObscuraValue))),
        ("render", CFUNCTYPE(_S, _D, POINTER(ObscuraRenderPassDesc))),
        ("mapRenderBuffer", CFUNCTYPE(_S, _D, c_char_p, POINTER(ObscuraMappedBuffer))),
        ("unmapRenderBuffer", CFUNCTYPE(_S, _D, c_char_p)),
        ("getPassTimings", CFUNCTYPE(_S, _D, POINTER(ObscuraPassTiming), POINTER(c_uint32))),
        ("getRenderStats", CFUNCTYPE(_S, _D, POINTER(ObscuraRenderStats))),
        ("enumerateDevices", CFUNCTYPE(_S, POINTER(ObscuraDeviceInfo), POINTER(c_uint32))),
        ("getPrimId", CFUNCTYPE(_S, _D, c_char_p, POINTER(c_int32))),
        ("describeRenderSetting", CFUNCTYPE(_S, c_uint32, POINTER(c_char_p), POINTER(c_char_p))),
    ]


PFN_obscuraGetApi = CFUNCTYPE(c_enum, c_uint32, c_uint32, POINTER(c_void_p))

# Every mirrored type by its C name, for the layout check.
STRUCTS = {
    "ObscuraValue": ObscuraValue,
    "ObscuraDelegateCreateInfo": ObscuraDelegateCreateInfo,
    "ObscuraSceneDelegate": ObscuraSceneDelegate,
    "ObscuraAovBinding": ObscuraAovBinding,
    "ObscuraRenderPassDesc": ObscuraRenderPassDesc,
    "ObscuraMappedBuffer": ObscuraMappedBuffer,
    "ObscuraDeviceInfo": ObscuraDeviceInfo,
    "ObscuraPassTiming": ObscuraPassTiming,
    "ObscuraMemoryStats": ObscuraMemoryStats,
    "ObscuraCullingStats": ObscuraCullingStats,
    "ObscuraRenderStats": ObscuraRenderStats,
    "ObscuraApiV1": ObscuraApiV1,
}
