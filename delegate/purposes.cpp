#include "delegate/purposes.h"

namespace obscura::delegate {

uint32_t purposeBit(std::string_view token) {
    if (token == "default") return kPurposeDefault;
    if (token == "render") return kPurposeRender;
    if (token == "proxy") return kPurposeProxy;
    if (token == "guide") return kPurposeGuide;
    return 0;
}

uint32_t purposeMask(std::string_view list) {
    uint32_t mask = 0;
    for (size_t start = 0; start <= list.size();) {
        size_t end = list.find(',', start);
        if (end == std::string_view::npos) end = list.size();
        mask |= purposeBit(list.substr(start, end - start));
        start = end + 1;
    }
    return mask;
}

}  // namespace obscura::delegate
