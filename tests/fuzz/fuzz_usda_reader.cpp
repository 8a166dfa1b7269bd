// libFuzzer target: USD layers (text, or crate files by their first bytes) through the whole reader (lexer,
// parser or crate decoding, composition) and the stage's evaluation. Any input must end in a Stage or an
// Error, within the limits.
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness/usda/stage.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace obscura::usda;
    // Small limits keep each input fast and bounded; the defaults are tested in tests/usda.
    StageOptions options;
    options.limits.maxPrims = 20000;
    options.limits.maxMemoryBytes = size_t(256) << 20;
    auto result = Stage::openFromString(std::string(reinterpret_cast<const char*>(data), size), "fuzz.usda", options);
    auto* stage = std::get_if<std::unique_ptr<Stage>>(&result);
    if (!stage) return 0;
    for (const Prim* prim : (*stage)->prims()) {
        (*stage)->worldTransform(*prim, 1.0);
        (*stage)->isVisible(*prim, 1.0);
        for (const auto& entry : prim->attributes) entry.second.evaluate(12.5);
    }
    return 0;
}
