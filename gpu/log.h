// A logging sink the delegate connects to the host's log callback.
#pragma once

#include <functional>
#include <string>

namespace obscura {

enum class LogLevel { Debug, Info, Warning, Error };

using LogSink = std::function<void(LogLevel, const std::string&)>;

}  // namespace obscura
