// OpenUSD's global variant fallbacks from plugins: UsdStage takes each registered plugin's
// Info["UsdVariantFallbacks"] ({"shadingVariant": ["Default"]}: a variant set with no authored
// selection takes the first of those variants it has), from the plugInfo.json files found on
// PXR_PLUGINPATH_NAME. The harness reads them the same way, without loading any plugin, and the
// command line's --variant-fallback replaces them set by set.
#pragma once

#include "harness/usda/stage.h"

#include <string>
#include <vector>

namespace obscura::harness {

struct PluginVariantFallbacks {
    usda::VariantFallbacks fallbacks;
    // A plugInfo.json that cannot be read or parsed (file:line:column of the fault), or whose
    // UsdVariantFallbacks is not a map of sets to variant name lists: that file or entry is ignored.
    std::vector<usda::Warning> warnings;
};

// `searchPath`: colon-separated plugInfo.json files or folders (a folder's own plugInfo.json), as
// PXR_PLUGINPATH_NAME lists them; each file's "Includes" (paths or globs relative to the file,
// folders meaning their plugInfo.json) are read after it. Paths that hold no plugInfo.json are
// skipped quietly, as OpenUSD skips them; a set several plugins list takes the last one read.
PluginVariantFallbacks readPluginVariantFallbacks(const std::string& searchPath);

}  // namespace obscura::harness
