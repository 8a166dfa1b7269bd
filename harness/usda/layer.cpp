#include "harness/usda/layer.h"

namespace obscura::usda {

const PrimSpec* Layer::find(std::string_view sitePath) const {
    const PrimSpec* spec = &pseudoRoot;
    size_t pos = 1;
    while (spec && pos < sitePath.size()) {
        size_t end = sitePath.find_first_of("/{", pos);
        if (end == std::string_view::npos) end = sitePath.size();
        spec = spec->child(std::string(sitePath.substr(pos, end - pos)));
        // Variant selections "{set=variant}" descend into that variant's contents.
        while (spec && end < sitePath.size() && sitePath[end] == '{') {
            const size_t eq = sitePath.find('=', end);
            const size_t close = sitePath.find('}', end);
            if (eq == std::string_view::npos || close == std::string_view::npos || eq > close) return nullptr;
            const auto set = spec->variantSets.find(std::string(sitePath.substr(end + 1, eq - end - 1)));
            if (set == spec->variantSets.end()) return nullptr;
            const auto variant = set->second.variants.find(std::string(sitePath.substr(eq + 1, close - eq - 1)));
            spec = variant == set->second.variants.end() ? nullptr : variant->second.get();
            end = close + 1;
        }
        pos = end + 1;
    }
    return spec;
}

}  // namespace obscura::usda
