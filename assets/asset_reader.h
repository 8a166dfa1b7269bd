// The bytes of the files asset paths name: a plain file, or a file inside a USDZ package
// ("a.usdz[tex/b.png]", a package inside a package too; package_path.h), read from the archive in
// memory and never unpacked to disk. The one way the harness (layers) and the plugin (textures)
// read what an asset path names.
#pragma once

#include "assets/usdz_package.h"

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace obscura::assets {

// Each package is opened on first use and kept open while the reader lives (its file open, its
// files read as they are asked for), so that the files of one package (a stage's layers, a UDIM
// set's tiles) share one opening. Readers are made for one piece of work (composing a stage,
// loading a texture) and then dropped: the next sees a package changed on disk. Not thread-safe:
// one thread at a time.
class AssetReader {
public:
    // The bytes of the file `path` names; nullopt, and `error` set to why, when it cannot be read.
    std::optional<std::string> read(const std::string& path, std::string* error);
    // The package at `path`, a file or a package path; nullptr, and `error` set, when it cannot
    // be opened. Failures are not remembered.
    const UsdzPackage* package(const std::string& path, std::string* error);

private:
    std::map<std::string, std::unique_ptr<UsdzPackage>> packages_;
};

}  // namespace obscura::assets
