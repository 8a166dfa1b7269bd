/* A host written in C99: finds the plugin through its plugInfo.json, dlopens it, negotiates the
 * ABI, supplies a scene delegate in C and reads an AOV back; every entry point is held through its
 * PFN_ typedef, and the log must hold no error but the one the bad mesh provokes. Exits 0 when
 * every check passes. */
#include <obscura/grading_chart.h> /* compiles as C too */
#include <obscura/obscura.h>

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond, ...)                                     \
    do {                                                     \
        if (!(cond)) {                                       \
            fprintf(stderr, "FAILED %s:%d: ", __FILE__, __LINE__); \
            fprintf(stderr, __VA_ARGS__);                    \
            fprintf(stderr, "\n");                           \
            ++failures;                                      \
        }                                                    \
    } while (0)

/* The value of the first "LibraryPath" key in plugInfo.json (a C host without a JSON library
 * reads just this key). */
static int readLibraryPath(const char* dir, char* out, size_t size) {
    char file[4096];
    snprintf(file, sizeof file, "%s/plugInfo.json", dir);
    FILE* f = fopen(file, "rb");
    if (!f) return 0;
    static char text[1 << 16];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    const char* key = strstr(text, "\"LibraryPath\"");
    if (!key) return 0;
    const char* q1 = strchr(key + 13, '"');
    const char* q2 = q1 ? strchr(q1 + 1, '"') : NULL;
    if (!q2) return 0;
    snprintf(out, size, "%s/%.*s", dir, (int)(q2 - q1 - 1), q1 + 1);
    return 1;
}

/* --- the scene ------------------------------------------------------------------------------ */
static const float kTriangle[9] = {-5.0f, -5.0f, 0.0f, 5.0f, -5.0f, 0.0f, 0.0f, 5.0f, 0.0f};
static const float kSmallTriangle[9] = {-0.5f, -0.5f, 0.1f, 0.5f, -0.5f, 0.1f, 0.0f, 0.5f, 0.1f};
static float badPoints[9];
static const int32_t kCounts[1] = {3};
static const int32_t kIndices[3] = {0, 1, 2};
static const int32_t kDimensions[2] = {32, 32};
static const char* kFormat = "int32";
static const float kFocal = 50.0f;
static int getValueCalls = 0;

/* The plugin's log: errors are counted, and those naming /BadMesh (the one this host provokes)
 * apart from the rest. */
static int loggedErrors = 0;
static int badMeshErrors = 0;
static void logMessage(void* user, ObscuraLogLevel level, const char* message) {
    (void)user;
    if (level != OBSCURA_LOG_ERROR) return;
    ++loggedErrors;
    if (strstr(message, "/BadMesh") != NULL) ++badMeshErrors;
    else fprintf(stderr, "logged error: %s\n", message);
}

static ObscuraStatus getValue(void* user, const char* path, const char* attribute, double time, ObscuraValue* out) {
    (void)user;
    (void)time;
    ++getValueCalls;
    if (strcmp(path, "/Buffer") == 0) {
        if (strcmp(attribute, "dimensions") == 0) {
            out->type = OBSCURA_VALUE_INT2; out->isArray = 0; out->count = 1; out->data = kDimensions;
            return OBSCURA_OK;
        }
        if (strcmp(attribute, "format") == 0) {
            out->type = OBSCURA_VALUE_TOKEN; out->isArray = 0; out->count = 1; out->data = &kFormat;
            return OBSCURA_OK;
        }
        return OBSCURA_ERROR_NOT_FOUND;
    }
    if (strcmp(path, "/Camera") == 0 && strcmp(attribute, "focalLength") == 0) {
        out->type = OBSCURA_VALUE_FLOAT; out->isArray = 0; out->count = 1; out->data = &kFocal;
        return OBSCURA_OK;
    }
    if (strcmp(path, "/Mesh") == 0 || strcmp(path, "/BadMesh") == 0) {
        int bad = strcmp(path, "/BadMesh") == 0;
        if (strcmp(attribute, "points") == 0) {
            out->type = OBSCURA_VALUE_FLOAT3; out->isArray = 1; out->count = 3;
            out->data = bad ? badPoints : kTriangle;
            return OBSCURA_OK;
        }
        if (strcmp(attribute, "faceVertexCounts") == 0) {
            out->type = OBSCURA_VALUE_INT; out->isArray = 1; out->count = 1; out->data = kCounts;
            return OBSCURA_OK;
        }
        if (strcmp(attribute, "faceVertexIndices") == 0) {
            out->type = OBSCURA_VALUE_INT; out->isArray = 1; out->count = 3; out->data = kIndices;
            return OBSCURA_OK;
        }
    }
    return OBSCURA_ERROR_NOT_FOUND;
}

static ObscuraStatus sampleTransform(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                     double* times, double* matrices, uint32_t* count) {
    int i;
    (void)user;
    (void)t1;
    if (maxSamples < 1) return OBSCURA_ERROR_INVALID_ARGUMENT;
    for (i = 0; i < 16; ++i) matrices[i] = (i % 5 == 0) ? 1.0 : 0.0;
    if (strcmp(path, "/Camera") == 0) matrices[14] = 20.0; /* 20 units back along +Z */
    times[0] = t0;
    *count = 1;
    return OBSCURA_OK;
}

int main(void) {
    char library[4096];
    void* handle;
    PFN_obscuraGetApi getApi;
    const void* table = NULL;
    const ObscuraApiV1* api;
    ObscuraDelegate delegate = NULL;
    ObscuraDelegateCreateInfo info;
    ObscuraSceneDelegate scene;
    ObscuraAovBinding binding = {"primId", "/Buffer"};
    ObscuraRenderPassDesc desc;
    ObscuraMappedBuffer mapped;
    int32_t meshId = -1, centre, corner;
    int i;

    badPoints[0] = NAN;
    for (i = 1; i < 9; ++i) badPoints[i] = kSmallTriangle[i];

    CHECK(readLibraryPath(OBSCURA_TEST_PLUGIN_DIR, library, sizeof library), "no LibraryPath in plugInfo.json");
    handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
    CHECK(handle != NULL, "dlopen %s: %s", library, dlerror());
    if (!handle) return 1;
    *(void**)(&getApi) = dlsym(handle, OBSCURA_GET_API_SYMBOL);
    CHECK(getApi != NULL, "no %s", OBSCURA_GET_API_SYMBOL);
    if (!getApi) return 1;

    /* An unknown major version is refused, not crashed on. */
    CHECK(getApi(OBSCURA_ABI_VERSION_MAJOR + 1, 0, &table) == OBSCURA_ERROR_UNSUPPORTED_VERSION, "major+1 accepted");
    CHECK(table == NULL, "table returned for an unsupported version");
    CHECK(getApi(OBSCURA_ABI_VERSION_MAJOR, OBSCURA_ABI_VERSION_MINOR + 1, &table) == OBSCURA_ERROR_UNSUPPORTED_VERSION,
          "a newer minor version accepted");
    CHECK(getApi(OBSCURA_ABI_VERSION_MAJOR, OBSCURA_ABI_VERSION_MINOR, &table) == OBSCURA_OK, "ABI 1.0 refused");
    api = (const ObscuraApiV1*)table;
    CHECK(api && api->structSize >= sizeof(ObscuraApiV1), "table too small");
    if (!api) return 1;
    CHECK(getApi(OBSCURA_ABI_VERSION_MAJOR, 0, NULL) == OBSCURA_ERROR_INVALID_ARGUMENT, "NULL outTable accepted");
    {
        /* Every entry point has its PFN_ typedef (a C host loading them one by one needs it). */
        PFN_obscuraCreateDelegate createDelegate = api->createDelegate;
        PFN_obscuraDestroyDelegate destroyDelegate = api->destroyDelegate;
        PFN_obscuraLastError lastError = api->lastError;
        PFN_obscuraSetSceneDelegate setSceneDelegate = api->setSceneDelegate;
        PFN_obscuraInsertPrim insertPrim = api->insertPrim;
        PFN_obscuraRemovePrim removePrim = api->removePrim;
        PFN_obscuraMarkDirty markDirty = api->markDirty;
        PFN_obscuraSetRenderSetting setRenderSetting = api->setRenderSetting;
        PFN_obscuraRender render = api->render;
        PFN_obscuraMapRenderBuffer mapRenderBuffer = api->mapRenderBuffer;
        PFN_obscuraUnmapRenderBuffer unmapRenderBuffer = api->unmapRenderBuffer;
        PFN_obscuraGetPassTimings getPassTimings = api->getPassTimings;
        PFN_obscuraGetRenderStats getRenderStats = api->getRenderStats;
        PFN_obscuraEnumerateDevices enumerateDevices = api->enumerateDevices;
        PFN_obscuraGetPrimId getPrimId = api->getPrimId;
        PFN_obscuraDescribeRenderSetting describeRenderSetting = api->describeRenderSetting;
        CHECK(createDelegate && destroyDelegate && lastError && setSceneDelegate && insertPrim && removePrim &&
                  markDirty && setRenderSetting && render && mapRenderBuffer && unmapRenderBuffer && getPassTimings &&
                  getRenderStats && enumerateDevices && getPrimId && describeRenderSetting,
              "a NULL entry in the table");
    }

    memset(&info, 0, sizeof info);
    info.sType = OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO;
    info.structSize = sizeof info;
    info.validation = 1;
    info.log = logMessage;
    CHECK(api->createDelegate(&info, &delegate) == OBSCURA_OK, "createDelegate: %s", api->lastError(NULL));
    if (!delegate) return 1;

    memset(&scene, 0, sizeof scene);
    scene.sType = OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE;
    scene.structSize = sizeof scene;
    scene.getValue = getValue;
    scene.sampleTransform = sampleTransform;
    CHECK(api->setSceneDelegate(delegate, &scene) == OBSCURA_OK, "setSceneDelegate");
    CHECK(api->insertPrim(delegate, "camera", "/Camera") == OBSCURA_OK, "insert camera");
    CHECK(api->insertPrim(delegate, "mesh", "/Mesh") == OBSCURA_OK, "insert mesh");
    CHECK(api->insertPrim(delegate, "mesh", "/BadMesh") == OBSCURA_OK, "insert bad mesh");
    CHECK(api->insertPrim(delegate, "renderBuffer", "/Buffer") == OBSCURA_OK, "insert buffer");

    memset(&desc, 0, sizeof desc);
    desc.sType = OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC;
    desc.structSize = sizeof desc;
    desc.cameraPath = "/Camera";
    desc.aovBindingCount = 1;
    desc.aovBindings = &binding;
    /* The NaN mesh is skipped and reported; the other one still renders. */
    CHECK(api->render(delegate, &desc) == OBSCURA_ERROR_BAD_PRIM_DATA, "render: %s", api->lastError(delegate));
    CHECK(strstr(api->lastError(delegate), "/BadMesh") != NULL, "error does not name the prim: %s",
          api->lastError(delegate));

    memset(&mapped, 0, sizeof mapped);
    mapped.sType = OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER;
    mapped.structSize = sizeof mapped;
    CHECK(api->mapRenderBuffer(delegate, "/Buffer", &mapped) == OBSCURA_OK, "map: %s", api->lastError(delegate));
    CHECK(api->getPrimId(delegate, "/Mesh", &meshId) == OBSCURA_OK, "getPrimId");
    if (mapped.data) {
        centre = ((const int32_t*)mapped.data)[16 * 32 + 16];
        corner = ((const int32_t*)mapped.data)[0];
        CHECK(centre == meshId, "centre pixel holds %d, expected %d", centre, meshId);
        CHECK(corner == -1, "corner pixel holds %d, expected -1", corner);
    }
    CHECK(api->unmapRenderBuffer(delegate, "/Buffer") == OBSCURA_OK, "unmap");

    /* Nothing dirty: the second render pulls nothing. */
    getValueCalls = 0;
    api->render(delegate, &desc);
    CHECK(getValueCalls == 0, "%d getValue calls with nothing dirty", getValueCalls);

    CHECK(api->destroyDelegate(delegate) == OBSCURA_OK, "destroyDelegate");
    CHECK(badMeshErrors == 1, "%d errors name /BadMesh, expected 1", badMeshErrors);
    CHECK(loggedErrors == badMeshErrors, "%d logged errors the host did not provoke", loggedErrors - badMeshErrors);
    dlclose(handle);
    if (failures == 0) printf("c_host: all checks passed\n");
    return failures == 0 ? 0 : 1;
}
