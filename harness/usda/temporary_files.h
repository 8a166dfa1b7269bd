// Files the harness writes so that the plugin, which reads textures from files and USDZ packages,
// can open images embedded in a file Assimp imports (glTF, GLB, FBX). Each is written once per
// process under its key, into a temporary folder removed when the process exits.
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

// Every file written or adopted so far, by key.
std::map<std::string, std::string> temporaryFilesByKey();

// Takes on files a child process wrote: temporaryFile returns them for their keys from now on.
void adoptTemporaryFiles(const std::map<std::string, std::string>& files);

}  // namespace obscura::usda
