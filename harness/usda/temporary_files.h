// Files the harness writes so that readers of plain files (the delegate's texture loader) can open
// what lives only inside another file: textures in USDZ packages, images embedded in glTF. Each is
// written once per process under its key, into a temporary folder removed at exit.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace obscura::usda {

// The path of the file for `key`, named `fileName` (its extension is what image readers look at);
// `bytes` is asked for the contents only the first time. "" (and `error` set) on failure.
std::string temporaryFile(const std::string& key, const std::string& fileName,
                          const std::function<std::optional<std::string>(std::string* error)>& bytes,
                          std::string* error);

}  // namespace obscura::usda
