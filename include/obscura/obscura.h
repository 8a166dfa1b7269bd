/*
 * Obscura — public C ABI of the render delegate plugin.
 *
 * This is the only header a host compiles against. It is C99 and C++ compatible, carries no
 * STL type, no exception and no Vulkan handle. A host loads the plugin library (found through
 * plugInfo.json, see docs/INTEGRATION.md), looks up the single exported symbol
 * `obscuraGetApi` and asks for the function table of the ABI major version it was built for.
 *
 * Model (Hydra's): the host inserts prims by type and path, marks them dirty with dirty bits and,
 * on render, the delegate pulls the values of dirty prims through the scene-delegate callback
 * table the host supplied. A render pass draws a camera into render buffers (AOVs) that the
 * host maps for reading.
 *
 * Conventions
 *  - Every function returns an ObscuraStatus; on failure obscuraGetLastError-style
 *    `lastError(delegate)` returns a readable message (per delegate; per thread for calls that
 *    have no delegate yet).
 *  - Extensible structs start with `sType`, `pNext`, `structSize` (Vulkan style). Published
 *    structs never change; new fields arrive as new chained structs, new functions as a new
 *    table version. A host sets structSize = sizeof(struct) as it was compiled; an input struct
 *    with another sType or a smaller structSize is refused with OBSCURA_ERROR_INVALID_ARGUMENT,
 *    and so is an output struct whose structSize is smaller. Output structs the host passes one
 *    at a time (ObscuraRenderStats, ObscuraMappedBuffer) are filled without touching the host's
 *    sType, pNext and structSize; known structs chained to an output struct's pNext are filled
 *    too. Output arrays (ObscuraPassTiming, ObscuraDeviceInfo) are written whole, each element's
 *    sType and structSize set and its pNext NULL.
 *  - Parameters are marked [in] (read by the call) or [out] (written by it); the delegate handle
 *    is [in] everywhere. Every entry point that takes a delegate returns
 *    OBSCURA_ERROR_INVALID_ARGUMENT for a NULL delegate, every entry point
 *    OBSCURA_ERROR_INVALID_ARGUMENT for a NULL required pointer (pointers that may be NULL say
 *    so), OBSCURA_ERROR_INVALID_STATE for a call made while another call on the same delegate
 *    runs, OBSCURA_ERROR_OUT_OF_MEMORY when host or device memory ran out and
 *    OBSCURA_ERROR_INTERNAL for a bug; the codes each entry point adds are listed with it. A
 *    failed call changes nothing unless its description says otherwise.
 *  - Mapped render buffers: see mapRenderBuffer, the one place that says how long a mapping lasts.
 *  - Device failures: once a render returns OBSCURA_ERROR_DEVICE for a lost device, every later
 *    render is refused with it; destroy the delegate (which always succeeds) and create a new
 *    one. For tests, OBSCURA_FAULT_INJECTION=device-lost:N or out-of-memory:N, read when a
 *    delegate is created, makes its N-th render (1-based) fail that way.
 *  - Matrices are 16 doubles in USD's GfMatrix4d convention: row-major, row vectors
 *    (p' = p * M), translation in elements 12, 13, 14.
 *  - Paths are absolute prim paths ("/World/Mesh"), UTF-8, NUL-terminated.
 *
 * Thread-safety
 *  - `obscuraGetApi` and the table's `enumerateDevices` may be called from any thread.
 *  - Calls on one delegate must be serialised by the host (one thread at a time). Different
 *    delegates are independent and may be used concurrently from different threads. A call on a
 *    delegate made while another call on it runs (from a scene-delegate or log callback inside
 *    render, or from another thread) is refused with OBSCURA_ERROR_INVALID_STATE and changes
 *    nothing; its message is in lastError(delegate) when it came from a callback, in
 *    lastError(NULL) when it came from another thread. lastError itself may always be called.
 *  - Scene-delegate callbacks are invoked only on the thread that called `render`, unless the
 *    host sets OBSCURA_SCENE_DELEGATE_THREAD_SAFE in ObscuraSceneDelegate::flags: then sync pulls
 *    the dirty rprims (meshes, curves, points, implicit surfaces, instancers) on several threads
 *    of the plugin's own at once, each prim's callbacks on one thread and in order; cameras,
 *    lights, materials and render buffers are still pulled on the calling thread. An API call from
 *    a callback on one of those threads is refused as a call from another thread.
 *  - Log callbacks are invoked on the thread that made the call only.
 */
#ifndef OBSCURA_OBSCURA_H
#define OBSCURA_OBSCURA_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32)
#define OBSCURA_EXPORT __declspec(dllexport)
#else
#define OBSCURA_EXPORT __attribute__((visibility("default")))
#endif

#define OBSCURA_ABI_VERSION_MAJOR 1
#define OBSCURA_ABI_VERSION_MINOR 3  /* 1.1: ObscuraMemoryStats, PFN_ typedefs; 1.2: display interop;
                                        1.3: ObscuraMemoryStats by kind, ObscuraCullingStats */

/* ---------------------------------------------------------------------------------------------
 * Status codes
 * ------------------------------------------------------------------------------------------- */
typedef enum ObscuraStatus {
    OBSCURA_OK = 0,
    OBSCURA_ERROR_INVALID_ARGUMENT = 1,  /* null pointer, bad struct size, malformed value */
    OBSCURA_ERROR_UNSUPPORTED_VERSION = 2,/* ABI major version not provided by this plugin */
    OBSCURA_ERROR_NOT_FOUND = 3,         /* no prim / setting / AOV of that name */
    OBSCURA_ERROR_ALREADY_EXISTS = 4,    /* insertPrim on a path already in use */
    OBSCURA_ERROR_UNKNOWN_TYPE = 5,      /* prim type not supported (see plugInfo.json) */
    OBSCURA_ERROR_BAD_PRIM_DATA = 6,     /* render succeeded but some prims were skipped */
    OBSCURA_ERROR_DEVICE = 7,            /* Vulkan device missing, lost, or unable to do what was asked */
    OBSCURA_ERROR_VALIDATION = 8,        /* validation layer reported an error (OBSCURA_VALIDATION=1) */
    OBSCURA_ERROR_OUT_OF_MEMORY = 9,
    OBSCURA_ERROR_INVALID_STATE = 10,    /* e.g. map of a buffer never rendered, render without camera */
    OBSCURA_ERROR_INTERNAL = 11          /* a bug: please report with the message */
} ObscuraStatus;

/* ---------------------------------------------------------------------------------------------
 * Values exchanged with the scene delegate and render settings
 * ------------------------------------------------------------------------------------------- */
typedef enum ObscuraValueType {
    OBSCURA_VALUE_NONE = 0,
    OBSCURA_VALUE_BOOL = 1,        /* int32_t, 0 or 1 */
    OBSCURA_VALUE_INT = 2,         /* int32_t */
    OBSCURA_VALUE_FLOAT = 3,       /* float */
    OBSCURA_VALUE_DOUBLE = 4,      /* double */
    OBSCURA_VALUE_FLOAT2 = 5,      /* float[2] */
    OBSCURA_VALUE_FLOAT3 = 6,      /* float[3] (point3f, vector3f, normal3f, color3f) */
    OBSCURA_VALUE_FLOAT4 = 7,      /* float[4] */
    OBSCURA_VALUE_INT2 = 8,        /* int32_t[2] */
    OBSCURA_VALUE_MATRIX4D = 9,    /* double[16], see convention above */
    OBSCURA_VALUE_TOKEN = 10,      /* const char* (token, string, asset path) */
    OBSCURA_VALUE_PATH = 11        /* const char* (prim path; relationship target) */
} ObscuraValueType;

/*
 * A value: `count` elements of `type` at `data`. count == 1 for a scalar; an array attribute
 * (points, faceVertexIndices...) has count = number of elements and isArray = 1.
 * For TOKEN and PATH, data points to an array of `count` const char* pointers.
 * Lifetime: memory the host returns from a callback must stay valid until the next callback
 * on the same delegate (with OBSCURA_SCENE_DELEGATE_THREAD_SAFE: on the same thread) or until the
 * render call returns, whichever comes first; the delegate copies what it keeps.
 */
typedef struct ObscuraValue {
    ObscuraValueType type;
    int32_t isArray;
    size_t count;
    const void* data;
} ObscuraValue;

/* Interpolation of a primvar (as UsdGeomPrimvar). Returned by getPrimvarInterpolation. */
typedef enum ObscuraInterpolation {
    OBSCURA_INTERPOLATION_CONSTANT = 0,
    OBSCURA_INTERPOLATION_UNIFORM = 1,
    OBSCURA_INTERPOLATION_VARYING = 2,
    OBSCURA_INTERPOLATION_VERTEX = 3,
    OBSCURA_INTERPOLATION_FACE_VARYING = 4
} ObscuraInterpolation;

/* ---------------------------------------------------------------------------------------------
 * Prim types and dirty bits
 *
 * Prim type names (tokens): "mesh", "cube", "sphere", "cylinder", "cylinder1", "cone", "capsule",
 * "capsule1", "plane", "basisCurves", "nurbsPatch", "points", "instancer" (rprims); "camera",
 * "distantLight", "sphereLight", "rectLight", "diskLight", "cylinderLight", "domeLight", "material"
 * (sprims); "renderBuffer" (bprim). The schema reference (docs/schemas.md) lists every attribute,
 * its type, default, unit and whether it may be time-sampled.
 * ------------------------------------------------------------------------------------------- */
typedef uint32_t ObscuraDirtyBits;
#define OBSCURA_DIRTY_CLEAN        0x0000u
#define OBSCURA_DIRTY_TRANSFORM    0x0001u  /* transform (sampled over the shutter) */
#define OBSCURA_DIRTY_POINTS       0x0002u  /* points */
#define OBSCURA_DIRTY_TOPOLOGY     0x0004u  /* faceVertexCounts, faceVertexIndices, orientation */
#define OBSCURA_DIRTY_NORMALS      0x0008u  /* normals */
#define OBSCURA_DIRTY_PRIMVAR      0x0010u  /* primvars:* */
#define OBSCURA_DIRTY_MATERIAL_ID  0x0020u  /* material:binding */
#define OBSCURA_DIRTY_PARAMS       0x0040u  /* camera, light, material, render buffer parameters */
#define OBSCURA_DIRTY_VISIBILITY   0x0080u  /* visibility */
#define OBSCURA_DIRTY_DOUBLE_SIDED 0x0100u  /* doubleSided */
#define OBSCURA_DIRTY_ALL          0xFFFFFFFFu

/* ---------------------------------------------------------------------------------------------
 * Extensible structure types
 * ------------------------------------------------------------------------------------------- */
typedef enum ObscuraStructureType {
    OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO = 1,
    OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE = 2,
    OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC = 3,
    OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER = 4,
    OBSCURA_STRUCTURE_TYPE_DEVICE_INFO = 5,
    OBSCURA_STRUCTURE_TYPE_PASS_TIMING = 6,
    OBSCURA_STRUCTURE_TYPE_RENDER_STATS = 7,
    OBSCURA_STRUCTURE_TYPE_MEMORY_STATS = 8,    /* ABI 1.1 */
    OBSCURA_STRUCTURE_TYPE_EXTERNAL_BUFFER = 9, /* ABI 1.2 */
    OBSCURA_STRUCTURE_TYPE_INTEROP_STATS = 10,  /* ABI 1.2 */
    OBSCURA_STRUCTURE_TYPE_CULLING_STATS = 11   /* ABI 1.3 */
} ObscuraStructureType;

/* The head every extensible struct starts with, for walking pNext chains. */
typedef struct ObscuraStructHeader {
    ObscuraStructureType sType;
    const void* pNext;
    uint32_t structSize;
} ObscuraStructHeader;

typedef struct ObscuraDelegate_T* ObscuraDelegate;

typedef enum ObscuraLogLevel {
    OBSCURA_LOG_DEBUG = 0,
    OBSCURA_LOG_INFO = 1,
    OBSCURA_LOG_WARNING = 2,
    OBSCURA_LOG_ERROR = 3
} ObscuraLogLevel;

/* Implemented by the host: [in] message (valid during the call) at [in] level. */
typedef void (*PFN_obscuraLog)(void* userData, ObscuraLogLevel level, const char* message);

/* Creation of a delegate. */
typedef struct ObscuraDelegateCreateInfo {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO */
    const void* pNext;
    uint32_t structSize;
    const char* device;             /* NULL: OBSCURA_DEVICE or best device; else name substring or index */
    int32_t validation;             /* -1: from OBSCURA_VALIDATION; 0 off; 1 on, errors fail render */
    PFN_obscuraLog log;             /* may be NULL: messages go to stderr at WARNING and above */
    void* logUserData;
} ObscuraDelegateCreateInfo;

/* Scene delegate: the callbacks through which sync pulls dirty prim data from the host.
 * OBSCURA_SCENE_DELEGATE_THREAD_SAFE in `flags`: the callbacks may run on several threads at once
 * (for different prims), and sync pulls rprims in parallel (see Thread-safety above). */
#define OBSCURA_SCENE_DELEGATE_THREAD_SAFE 0x1u

/* Implemented by the host: return OBSCURA_OK and fill [out] out with the value of [in] attribute of
 * the prim at [in] primPath at [in] time (the host's time codes), or OBSCURA_ERROR_NOT_FOUND when the
 * attribute is not authored (the delegate then uses the schema default). Any other status makes the
 * prim's data bad (it is skipped, see render). */
typedef ObscuraStatus (*PFN_obscuraGetValue)(void* userData, const char* primPath,
                                             const char* attribute, double time, ObscuraValue* out);
/* Implemented by the host: [out] the interpolation of primvar (or normals) [in] attribute of the
 * prim at [in] primPath; OBSCURA_ERROR_NOT_FOUND means the schema's default. */
typedef ObscuraStatus (*PFN_obscuraGetInterpolation)(void* userData, const char* primPath,
                                                     const char* attribute, ObscuraInterpolation* out);
/* Implemented by the host: sample the world transform of the prim at [in] primPath over [in]
 * [time0, time1] (like HdSceneDelegate::SampleTransform): write at most [in] maxSamples (time,
 * matrix) pairs, sorted by time, into [out] sampleTimes and matrices (16 doubles each), and their
 * number to [out] sampleCount. A prim without animation returns one sample; OBSCURA_ERROR_NOT_FOUND
 * means the identity. */
typedef ObscuraStatus (*PFN_obscuraSampleTransform)(void* userData, const char* primPath,
                                                    double time0, double time1, uint32_t maxSamples,
                                                    double* sampleTimes, double* matrices,
                                                    uint32_t* sampleCount);

typedef struct ObscuraSceneDelegate {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE */
    const void* pNext;
    uint32_t structSize;
    uint32_t flags;                 /* OBSCURA_SCENE_DELEGATE_THREAD_SAFE */
    void* userData;
    PFN_obscuraGetValue getValue;
    PFN_obscuraGetInterpolation getInterpolation;   /* may be NULL: schema defaults */
    PFN_obscuraSampleTransform sampleTransform;
} ObscuraSceneDelegate;

/* An AOV binding: render `aov` into the render buffer prim at `renderBufferPath`. AOVs:
 *   "color"   float32Vec4  linear, premultiplied RGBA, exposure applied (alpha 0 where nothing drew, unless the
 *                          camera sees a dome there, render setting domeLightCameraVisibility: alpha 1; transparent
 *                          surfaces of opacity a_i over it: 1 - (1 - opaque)(1 - a_1)(1 - a_2)...)
 *   "depth"   float32      clip-space depth in [0,1] (1 where nothing drew), as Hydra's depth AOV
 *   "normal"  float32Vec3  eye-space shading normal (Hydra's Neye); 0 where nothing drew
 *   "albedo"  float32Vec3  base colour of the surface
 *   "primId"  int32        id of the prim (see getPrimId), -1 where nothing drew; for a PointInstancer's
 *                          instance, its prototype mesh's
 *   "instanceId" int32     the instance's index in its PointInstancer's arrays (positions, protoIndices...),
 *                          -1 for a mesh drawn once and where nothing drew: with primId, what picking needs
 *   "display" unorm8Vec4   display-referred colour after the view transform (for PNG and viewports)
 *   "motion"  float32Vec3  screen-space displacement in pixels (x right, y down; z 0) of the surface from
 *                          the camera's shutter:open to shutter:close, camera and object motion together;
 *                          0 where the shutter is closed or the motionBlur setting is off
 * depth, normal, albedo, primId, instanceId and motion describe the nearest opaque surface: transparent surfaces (opacity
 * below 1 without opacityThreshold) are only in "color" and "display".
 * The render buffer's format must match the AOV's format above. */
typedef struct ObscuraAovBinding {
    const char* aov;
    const char* renderBufferPath;
} ObscuraAovBinding;

typedef struct ObscuraRenderPassDesc {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC */
    const void* pNext;
    uint32_t structSize;
    const char* cameraPath;         /* a "camera" prim */
    int32_t viewport[4];            /* x, y, width, height in pixels of the render buffers */
    double time;                    /* time code at which dirty prims are synced */
    uint32_t aovBindingCount;
    const ObscuraAovBinding* aovBindings;
} ObscuraRenderPassDesc;

typedef enum ObscuraFormat {
    OBSCURA_FORMAT_UNKNOWN = 0,
    OBSCURA_FORMAT_FLOAT32_VEC4 = 1,   /* RGBA float */
    OBSCURA_FORMAT_FLOAT32_VEC3 = 2,   /* XYZ float */
    OBSCURA_FORMAT_FLOAT32 = 3,        /* one float */
    OBSCURA_FORMAT_INT32 = 4,          /* one int32 */
    OBSCURA_FORMAT_UNORM8_VEC4 = 5     /* RGBA 8-bit, display-referred */
} ObscuraFormat;

/* A mapped render buffer: rows top to bottom, `rowStride` bytes apart; how long `data` stays valid:
 * see mapRenderBuffer. */
typedef struct ObscuraMappedBuffer {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER */
    const void* pNext;
    uint32_t structSize;
    uint32_t width;
    uint32_t height;
    ObscuraFormat format;
    size_t rowStride;
    const void* data;
} ObscuraMappedBuffer;

typedef struct ObscuraDeviceInfo {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_DEVICE_INFO */
    const void* pNext;
    uint32_t structSize;
    char name[256];
    char driver[256];
    uint32_t apiVersion;            /* VK_MAKE_API_VERSION packing */
    int32_t isDiscrete;
    int32_t isCpu;
    uint32_t maxMsaaSamples;
} ObscuraDeviceInfo;

/* Per-pass GPU timing of the last render, from timestamp queries. */
typedef struct ObscuraPassTiming {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_PASS_TIMING */
    const void* pNext;
    uint32_t structSize;
    char pass[64];
    double milliseconds;
} ObscuraPassTiming;

/* Counters of the last render. */
typedef struct ObscuraRenderStats {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_RENDER_STATS */
    const void* pNext;
    uint32_t structSize;
    uint32_t primsSynced;           /* prims whose Sync ran in the last render */
    uint32_t primsSkipped;          /* prims currently skipped because of bad data */
    uint32_t validationErrors;      /* validation messages of error severity so far */
    uint32_t converged;             /* 1 when another render of an unchanged scene adds nothing */
    uint64_t trianglesDrawn;
    char deviceName[256];           /* the Vulkan device this delegate renders with */
    double syncMilliseconds;        /* CPU time of the last render's sync (pulls, rebuilds, uploads) */
    double frameSetupMilliseconds;  /* CPU time packing per-frame records and recording the frame */
    uint64_t geometryBytes;         /* vertex + index data on the GPU; identical meshes share one copy */
} ObscuraRenderStats;

/* ABI 1.1, chained to ObscuraRenderStats::pNext: the delegate's Vulkan memory now. A steady frame
 * allocates none: these stay put while an unchanged scene renders. A host built against 1.1 or 1.2
 * passes the smaller structSize and gets the first three counters; the 1.3 counters say what
 * deviceMemoryInUse holds (exported render buffers live in memory of their own, counted nowhere). */
typedef struct ObscuraMemoryStats {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_MEMORY_STATS */
    const void* pNext;
    uint32_t structSize;
    uint32_t deviceMemoryBlocks;    /* VkDeviceMemory allocations held */
    uint64_t deviceMemoryReserved;  /* bytes in those allocations */
    uint64_t deviceMemoryInUse;     /* bytes of them holding live buffers and images */
    /* ABI 1.3: parts of deviceMemoryInUse */
    uint64_t imageBytes;            /* in images; the rest is in buffers */
    uint64_t frameTargetBytes;      /* the frame's transient targets (G-buffer, ...), aliased where they can be */
    uint64_t frameHistoryBytes;     /* images kept between frames: histories, shadow atlas, environment maps */
    uint64_t textureBytes;          /* material textures */
    uint64_t geometryBytes;         /* vertex and index data */
    uint64_t renderBufferBytes;     /* render buffers (and device-local twins the AOVs are packed into) */
} ObscuraMemoryStats;

/* ABI 1.3, chained to ObscuraRenderStats::pNext: occlusion culling in the last render's camera
 * view (render setting occlusionCulling). The draws, instances and triangles the camera had to draw
 * before culling, and those occlusion culling hid: on the gpu route (occlusionCulling:route) what
 * the frame's own early depth hid, read back once the frame ran; on the coverageBuffer route what
 * the last frame's depth hid. All culled counts are 0 with the setting off and on the first frame,
 * and on the coverageBuffer route after a camera cut. A draw is one instanced draw call (meshes
 * sharing geometry, or an instancer's prototype). Shadow maps are not counted (the gpu route culls
 * their views' draws too; the coverageBuffer route draws every caster). */
typedef struct ObscuraCullingStats {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_CULLING_STATS */
    const void* pNext;
    uint32_t structSize;
    uint32_t draws;
    uint32_t drawsCulled;           /* draws none of whose instances were drawn */
    uint64_t instances;
    uint64_t instancesCulled;
    uint64_t triangles;
    uint64_t trianglesCulled;
    double milliseconds;            /* CPU time testing bounds (and reprojecting the coverage buffer) */
    /* Outside the camera's view frustum (culled always; not counted in the *Culled counts above) */
    uint32_t drawsOutsideView;
    uint64_t instancesOutsideView;
    uint64_t trianglesOutsideView;
} ObscuraCullingStats;

/* ---------------------------------------------------------------------------------------------
 * The function table, version 1.x (ABI 1.0's layout; 1.1 adds no function)
 * ------------------------------------------------------------------------------------------- */

/* Create a delegate (owns a Vulkan device); several may live in one process. [in] info: NULL for
 * defaults, else sType/structSize checked. [out] outDelegate (NULL on failure).
 * OBSCURA_ERROR_INVALID_ARGUMENT: outDelegate NULL, wrong sType or structSize.
 * OBSCURA_ERROR_DEVICE: no usable Vulkan device (or validation asked for and not installed).
 * Message: lastError(NULL). */
typedef ObscuraStatus (*PFN_obscuraCreateDelegate)(const ObscuraDelegateCreateInfo* info, ObscuraDelegate* outDelegate);
/* Destroy [in] delegate and every prim and buffer it holds (its mappings end). NULL is ignored
 * (OBSCURA_OK). Succeeds after any failure, a lost device included; OBSCURA_ERROR_INVALID_STATE
 * only while a call on the same delegate runs (from one of its callbacks, or on another thread). */
typedef ObscuraStatus (*PFN_obscuraDestroyDelegate)(ObscuraDelegate delegate);
/* Message of the last failed call on [in] delegate (NULL: the last failed call on this thread that
 * had no delegate, had a NULL delegate, or was refused as concurrent from another thread). Valid
 * until the next call on that delegate (on this thread, for NULL). Never NULL: "" before any
 * failure; a successful call leaves the last message in place. Returns no status. */
typedef const char* (*PFN_obscuraLastError)(ObscuraDelegate delegate);
/* Install the scene delegate [in] sceneDelegate (copied); every prim becomes fully dirty. Must be
 * called before the first render (render: OBSCURA_ERROR_INVALID_STATE).
 * OBSCURA_ERROR_INVALID_ARGUMENT: NULL, wrong sType/structSize, getValue NULL. */
typedef ObscuraStatus (*PFN_obscuraSetSceneDelegate)(ObscuraDelegate delegate, const ObscuraSceneDelegate* sceneDelegate);
/* Insert a prim of [in] type at [in] path; it starts fully dirty. OBSCURA_ERROR_INVALID_ARGUMENT:
 * path not absolute. OBSCURA_ERROR_UNKNOWN_TYPE: type not supported. OBSCURA_ERROR_ALREADY_EXISTS:
 * a prim lives at path (it stays as it was). */
typedef ObscuraStatus (*PFN_obscuraInsertPrim)(ObscuraDelegate delegate, const char* type, const char* path);
/* Remove the prim at [in] path (a render buffer's mapping ends with it); its GPU resources are
 * released at the end of the next frame. OBSCURA_ERROR_NOT_FOUND: no prim there. */
typedef ObscuraStatus (*PFN_obscuraRemovePrim)(ObscuraDelegate delegate, const char* path);
/* OR [in] bits into the prim at [in] path; the next render syncs it (OBSCURA_DIRTY_CLEAN marks
 * nothing). OBSCURA_ERROR_NOT_FOUND: no prim there. */
typedef ObscuraStatus (*PFN_obscuraMarkDirty)(ObscuraDelegate delegate, const char* path, ObscuraDirtyBits bits);
/* Set the render setting [in] key (see describeRenderSetting / `obscura info`) to [in] value; NULL
 * resets it to its default. OBSCURA_ERROR_NOT_FOUND: unknown key. OBSCURA_ERROR_INVALID_ARGUMENT:
 * wrong value type or a value out of range or not offered by the device (the setting keeps its
 * previous value). */
typedef ObscuraStatus (*PFN_obscuraSetRenderSetting)(ObscuraDelegate delegate, const char* key, const ObscuraValue* value);
/* Sync dirty prims at desc->time, then render the camera into the bound render buffers [in] desc.
 * OBSCURA_OK: every bound buffer holds this frame.
 * OBSCURA_ERROR_BAD_PRIM_DATA: prims (meshes, lights, materials, render buffers, ...) were skipped
 *   for bad data; the image is still rendered without them into every good buffer (a skipped
 *   render buffer keeps what it held); the log names each, lastError the first.
 * Refused, nothing rendered: OBSCURA_ERROR_INVALID_ARGUMENT (wrong sType/structSize, NULL names,
 *   unknown AOV format pairing, buffers of differing sizes, an empty viewport without buffers, a
 *   size beyond the device's largest image, colour management failing);
 *   OBSCURA_ERROR_NOT_FOUND (no camera, render buffer or AOV of that name);
 *   OBSCURA_ERROR_INVALID_STATE (no scene delegate; a bound buffer is mapped: unmap it first; a
 *   mapped buffer that is not bound keeps its mapping, see mapRenderBuffer);
 *   OBSCURA_ERROR_BAD_PRIM_DATA with the camera named when the camera itself is bad.
 * OBSCURA_ERROR_DEVICE: the device failed or was lost (then every later render is refused: make a
 *   new delegate). OBSCURA_ERROR_OUT_OF_MEMORY: the frame did not fit; the scene stays as it was
 *   and a later render may succeed. OBSCURA_ERROR_VALIDATION: validation on and it reported an
 *   error (the frame was rendered). */
typedef ObscuraStatus (*PFN_obscuraRender)(ObscuraDelegate delegate, const ObscuraRenderPassDesc* desc);
/* Map the render buffer at [in] path for reading into [out] out (sType/pNext/structSize left as
 * set). How long a mapping lasts, said once for the whole ABI: `data` stays valid and its contents
 * unchanged until unmapRenderBuffer of the buffer, removePrim of it or destroyDelegate, whatever
 * else happens meanwhile: render refuses to write a mapped buffer bound to it, renders into other
 * buffers leave it alone, and a new size or format it is given takes effect at its first render
 * after unmap. Mapping a mapped buffer again returns the same pointer.
 * OBSCURA_ERROR_INVALID_ARGUMENT: out->structSize too small. OBSCURA_ERROR_NOT_FOUND: no render
 * buffer there. OBSCURA_ERROR_INVALID_STATE: never rendered since it was inserted or resized. */
typedef ObscuraStatus (*PFN_obscuraMapRenderBuffer)(ObscuraDelegate delegate, const char* path, ObscuraMappedBuffer* out);
/* End the mapping of [in] path (one unmap ends any number of maps; unmapping an unmapped buffer
 * is OK); the pointer mapRenderBuffer gave must not be used after. OBSCURA_ERROR_NOT_FOUND: no
 * render buffer there. */
typedef ObscuraStatus (*PFN_obscuraUnmapRenderBuffer)(ObscuraDelegate delegate, const char* path);
/* Per-pass GPU timings of the last render (none before the first): with [out] timings == NULL
 * writes the count to [in,out] count, else fills min(*count, available) entries and writes that
 * number. No status of its own. */
typedef ObscuraStatus (*PFN_obscuraGetPassTimings)(ObscuraDelegate delegate, ObscuraPassTiming* timings, uint32_t* count);
/* Counters of the last render (zero before the first) into [out] out and into the known structs
 * chained to out->pNext (ObscuraMemoryStats; unknown ones are skipped); sType, pNext and
 * structSize of each are left as the host set them. OBSCURA_ERROR_INVALID_ARGUMENT:
 * out->structSize too small. */
typedef ObscuraStatus (*PFN_obscuraGetRenderStats)(ObscuraDelegate delegate, ObscuraRenderStats* out);
/* Vulkan devices visible to the plugin: with [out] devices == NULL writes the count to [in,out]
 * count, else fills min(*count, available) and writes that number. OBSCURA_ERROR_DEVICE: no
 * Vulkan instance. Message: lastError(NULL). Thread-safe. */
typedef ObscuraStatus (*PFN_obscuraEnumerateDevices)(ObscuraDeviceInfo* devices, uint32_t* count);
/* The integer the prim at [in] path writes into the primId AOV, into [out] outId (stable for the
 * prim's lifetime; -1 is "nothing"). OBSCURA_ERROR_NOT_FOUND: no prim there, or a prim that draws
 * nothing (cameras, lights, materials, render buffers, instancers). */
typedef ObscuraStatus (*PFN_obscuraGetPrimId)(ObscuraDelegate delegate, const char* path, int32_t* outId);
/* Render settings: [out] name and description (either may be NULL) of setting [in] index
 * (0-based); OBSCURA_ERROR_NOT_FOUND past the end. Strings are static. Takes no delegate.
 * Thread-safe. */
typedef ObscuraStatus (*PFN_obscuraDescribeRenderSetting)(uint32_t index, const char** name, const char** description);

typedef struct ObscuraApiV1 {
    uint32_t structSize;
    uint16_t versionMajor;
    uint16_t versionMinor;
    PFN_obscuraCreateDelegate createDelegate;
    PFN_obscuraDestroyDelegate destroyDelegate;
    PFN_obscuraLastError lastError;
    PFN_obscuraSetSceneDelegate setSceneDelegate;
    PFN_obscuraInsertPrim insertPrim;
    PFN_obscuraRemovePrim removePrim;
    PFN_obscuraMarkDirty markDirty;
    PFN_obscuraSetRenderSetting setRenderSetting;
    PFN_obscuraRender render;
    PFN_obscuraMapRenderBuffer mapRenderBuffer;
    PFN_obscuraUnmapRenderBuffer unmapRenderBuffer;
    PFN_obscuraGetPassTimings getPassTimings;
    PFN_obscuraGetRenderStats getRenderStats;
    PFN_obscuraEnumerateDevices enumerateDevices;
    PFN_obscuraGetPrimId getPrimId;
    PFN_obscuraDescribeRenderSetting describeRenderSetting;
} ObscuraApiV1;

/* =============================================================================================
 * ABI 1.2: display interop. A host that draws on the same GPU takes a render buffer's pixels
 * without a copy to host memory: the plugin exports the buffer's device memory as a Vulkan
 * external memory handle (VK_KHR_external_memory_fd, opaque fd) and, where the device can, a
 * timeline semaphore (VK_KHR_external_semaphore_fd) its frames signal. The host imports both on
 * its own VkDevice of the same physical device (matching deviceUUID and driverUUID) and reads the
 * pixels there (a Vulkan host as a storage or transfer-source buffer; a GL host through
 * GL_EXT_memory_object_fd and GL_EXT_semaphore_fd, see docs/INTEGRATION.md). An exported buffer
 * is written by the frame directly in device-local memory: no copy to host-visible memory
 * ("aov_copy") is made for it.
 * ============================================================================================= */

/* An exported render buffer (exportRenderBuffer's output). The pixels are laid out as a mapped
 * buffer's: `height` rows, top to bottom, `rowStride` bytes apart, from offset 0 of the memory. */
typedef struct ObscuraExternalBuffer {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_EXTERNAL_BUFFER */
    const void* pNext;
    uint32_t structSize;
    uint32_t width;
    uint32_t height;
    ObscuraFormat format;
    size_t rowStride;
    uint64_t size;                  /* bytes of pixels: height * rowStride */
    /* The VkDeviceMemory as an opaque fd (VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT), a new
     * descriptor per call that the host owns: vkAllocateMemory with VkImportMemoryFdInfoKHR takes
     * it over; a host that does not import it closes it. */
    int32_t memoryFd;
    uint64_t allocationSize;        /* VkMemoryAllocateInfo::allocationSize to import with */
    uint32_t memoryTypeIndex;       /* VkMemoryAllocateInfo::memoryTypeIndex to import with */
    /* 1: the memory is a dedicated allocation; import it with VkMemoryDedicatedAllocateInfo naming
     * the host's buffer (created with VkExternalMemoryBufferCreateInfo, OPAQUE_FD, `size` bytes). */
    int32_t dedicated;
    /* A timeline semaphore as an opaque fd (VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT), owned
     * by the host as memoryFd is; every render that writes the buffer signals it with that render's
     * ObscuraInteropStats::semaphoreValue once the frame is done and the buffer released to
     * VK_QUEUE_FAMILY_EXTERNAL. -1 where the device cannot export semaphores (lavapipe): render
     * returns only when its frame is done, so the host reads after render returns. */
    int32_t semaphoreFd;
    uint8_t deviceUUID[16];         /* VkPhysicalDeviceIDProperties of the plugin's device */
    uint8_t driverUUID[16];
} ObscuraExternalBuffer;

/* ABI 1.2, chained to ObscuraRenderStats::pNext: the value the exported semaphores reach when
 * the last render's frame is done (0 before the first render that wrote an exported buffer). A
 * host's queue waits for it (VkTimelineSemaphoreSubmitInfo) before reading the buffer. */
typedef struct ObscuraInteropStats {
    ObscuraStructureType sType;     /* OBSCURA_STRUCTURE_TYPE_INTEROP_STATS */
    const void* pNext;
    uint32_t structSize;
    uint64_t semaphoreValue;
} ObscuraInteropStats;

/* Export the render buffer at [in] path into [out] out (structSize >= sizeof checked; sType,
 * pNext left as set). From then on the buffer lives in exportable device memory that every render
 * writes directly (it holds the frame of the next render on); it cannot be mapped (mapRenderBuffer:
 * OBSCURA_ERROR_INVALID_STATE). The buffer
 * stays exported until removed; when its dimensions or format change the next render makes new
 * memory, which the host exports again (the old memory keeps the last frame until the host frees
 * its import). Calling it again returns new descriptors of the same memory and semaphore.
 * The host reads the memory only between a render's return (or its semaphore value) and the next
 * render. OBSCURA_ERROR_NOT_FOUND: no render buffer there. OBSCURA_ERROR_INVALID_STATE: never
 * rendered since it was inserted or resized, or it is mapped. OBSCURA_ERROR_DEVICE: the device
 * cannot export memory as an opaque fd (out->memoryFd is -1; read through mapRenderBuffer). */
typedef ObscuraStatus (*PFN_obscuraExportRenderBuffer)(ObscuraDelegate delegate, const char* path,
                                                       ObscuraExternalBuffer* out);

/* The function table of ABI 1.2: 1.0's table followed by the interop functions. obscuraGetApi(1, 2)
 * returns it; its `base.structSize` is sizeof(ObscuraApiV1_2) and base.versionMinor >= 2. A host
 * asking for 1.0 or 1.1 gets the same table and reads its first part. */
typedef struct ObscuraApiV1_2 {
    ObscuraApiV1 base;
    PFN_obscuraExportRenderBuffer exportRenderBuffer;
} ObscuraApiV1_2;

/* ============================================================================================= */

/*
 * The one exported entry point. Returns in [out] outTable a pointer to a static function table
 * whose major version equals [in] versionMajor and whose minor version is >= [in] versionMinor;
 * the table's first member is its size. OBSCURA_ERROR_UNSUPPORTED_VERSION (and *outTable = NULL,
 * message in lastError(NULL)) for any other request; OBSCURA_ERROR_INVALID_ARGUMENT: outTable
 * NULL. Thread-safe.
 */
OBSCURA_EXPORT ObscuraStatus obscuraGetApi(uint32_t versionMajor, uint32_t versionMinor, const void** outTable);
typedef ObscuraStatus (*PFN_obscuraGetApi)(uint32_t versionMajor, uint32_t versionMinor, const void** outTable);

#define OBSCURA_GET_API_SYMBOL "obscuraGetApi"

#ifdef __cplusplus
}
#endif

#endif /* OBSCURA_OBSCURA_H */
