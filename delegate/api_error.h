// A failure of an ABI call: its status and message (api.cpp turns it into the return value and
// the delegate's last error).
#pragma once

#include <obscura/obscura.h>

#include <string>

namespace obscura::delegate {

struct ApiError {
    ObscuraStatus status;
    std::string message;
};

}  // namespace obscura::delegate
