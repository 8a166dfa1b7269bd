// Simulated device failures, so that hosts and tests can see what a lost device or a failed
// allocation does without a driver that fails on cue. OBSCURA_FAULT_INJECTION, read when a delegate
// is created, names one fault and the render (1-based, counted per delegate) it strikes:
//   device-lost:N     the frame's queue submission of render N fails with VK_ERROR_DEVICE_LOST
//   out-of-memory:N   every device-memory allocation during render N fails with
//                     VK_ERROR_OUT_OF_DEVICE_MEMORY
#pragma once

#include <cstdint>
#include <string>

namespace obscura::gpu {

class FaultInjection {
public:
    enum class Kind { None, DeviceLost, OutOfMemory };
    // Parses "device-lost:N" / "out-of-memory:N"; anything else (or nothing) injects nothing and,
    // when not empty, is reported in `problem`.
    static FaultInjection parse(const std::string& spec, std::string* problem);
    static FaultInjection fromEnvironment(std::string* problem);

    void beginRender() { ++render_; }
    // Whether the operation of `kind` happening now must fail.
    bool strikes(Kind kind) const { return kind_ == kind && render_ == strikeRender_; }

private:
    Kind kind_ = Kind::None;
    uint64_t strikeRender_ = 0;
    uint64_t render_ = 0;
};

}  // namespace obscura::gpu
