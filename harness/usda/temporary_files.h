// Files the harness writes so that readers of plain files (the delegate's texture loader) can open
// what lives only inside another file: textures in USDZ packages, images embedded in glTF. Each is
// written once per process under its key, into a temporary folder removed when the process exits.
//
// A child process of the harness (an isolated import, harness/import/child_server.h) writes into
// its parent's folder, under names of its own, and hands what it wrote to the parent, which adopts
// the files: it reuses them and removes them with the rest.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>

namespace obscura::usda {

// The path of the file for `key`, named `fileName` (its extension is what image readers look at);
// `bytes` is asked for the contents only the first time. "" (and `error` set) on failure.
std::string temporaryFile(const std::string& key, const std::string& fileName,
                          const std::function<std::optional<std::string>(std::string* error)>& bytes,
                          std::string* error);

// Files that must lie side by side (the tiles of a UDIM set), named `fileName`, as `files`: a
// folder of their own, written once under `key`, holding each by its name. The path of `fileName`
// in that folder (a pattern may name no one file); "" (and `error` set) on failure.
using NamedFiles = std::map<std::string, std::string>;  // file name -> contents
std::string temporaryFolder(const std::string& key, const std::string& fileName,
                            const std::function<std::optional<NamedFiles>(std::string* error)>& files,
                            std::string* error);

// Every file written or adopted so far, by key.
std::map<std::string, std::string> temporaryFilesByKey();

// Takes on files a child process wrote: temporaryFile returns them for their keys from now on.
void adoptTemporaryFiles(const std::map<std::string, std::string>& files);

}  // namespace obscura::usda
