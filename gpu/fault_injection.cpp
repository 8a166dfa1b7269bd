#include "gpu/fault_injection.h"

#include <cstdlib>

namespace obscura::gpu {

FaultInjection FaultInjection::parse(const std::string& spec, std::string* problem) {
    FaultInjection f;
    if (spec.empty()) return f;
    auto colon = spec.find(':');
    std::string name = spec.substr(0, colon);
    char* end = nullptr;
    unsigned long long render =
        colon == std::string::npos ? 0 : std::strtoull(spec.c_str() + colon + 1, &end, 10);
    bool numberOk = colon != std::string::npos && end && *end == '\0' && render > 0;
    if (numberOk && name == "device-lost") f.kind_ = Kind::DeviceLost;
    else if (numberOk && name == "out-of-memory") f.kind_ = Kind::OutOfMemory;
    else if (problem)
        *problem = "OBSCURA_FAULT_INJECTION='" + spec + "' is not device-lost:N or out-of-memory:N; nothing is injected";
    if (f.kind_ != Kind::None) f.strikeRender_ = render;
    return f;
}

FaultInjection FaultInjection::fromEnvironment(std::string* problem) {
    const char* env = std::getenv("OBSCURA_FAULT_INJECTION");
    return parse(env ? env : "", problem);
}

}  // namespace obscura::gpu
