// Render settings by name, as DESIGN.md names them everywhere (ABI, --set, docs). Only settings
// the frame honours are listed; `obscura info` prints this table.
#pragma once

#include <obscura/obscura.h>

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <variant>

namespace obscura::delegate {

struct RenderSettingInfo {
    const char* name;
    const char* description;
    ObscuraValueType type;
    double defaultNumber;
    // Numbers outside [minimum, maximum] are refused with a reason (none given: any finite value).
    double minimum = -std::numeric_limits<double>::infinity();
    double maximum = std::numeric_limits<double>::infinity();
    // Tokens: the accepted values, '|'-separated (none given: any token).
    const char* tokenChoices = nullptr;
    // Tokens: the value when unset (none given: "").
    const char* defaultToken = nullptr;
    // Tokens: a comma-separated list, each entry one of tokenChoices.
    bool tokenList = false;
};

const RenderSettingInfo* findRenderSetting(const std::string& name);
const RenderSettingInfo* renderSettingAt(uint32_t index);

class RenderSettings {
public:
    // Stores a value after checking its type; returns a reason on failure. nullptr resets.
    std::string set(const std::string& name, const ObscuraValue* value);
    double number(const std::string& name) const;
    std::string token(const std::string& name) const;  // the default token when unset
    uint64_t version() const { return version_; }

private:
    std::map<std::string, double> numbers_;
    std::map<std::string, std::string> tokens_;
    uint64_t version_ = 0;
};

}  // namespace obscura::delegate
