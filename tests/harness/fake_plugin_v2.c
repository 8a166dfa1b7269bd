/* A plugin that speaks only ABI 2.x: hosts built for 1.x must be refused cleanly. */
#include <obscura/obscura.h>

OBSCURA_EXPORT ObscuraStatus obscuraGetApi(uint32_t versionMajor, uint32_t versionMinor, const void** outTable) {
    (void)versionMinor;
    if (outTable) *outTable = 0;
    return versionMajor == 2 ? OBSCURA_ERROR_INTERNAL : OBSCURA_ERROR_UNSUPPORTED_VERSION;
}
