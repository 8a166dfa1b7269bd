// Shared helpers for the .usda reader tests.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <variant>

#include "harness/usda/stage.h"

namespace obscura::usda::test {

inline const std::string kDataDir = OBSCURA_USDA_TEST_DATA;

// The stage composed from `text`, or nullptr after recording the error as a test failure.
inline std::unique_ptr<Stage> open(const std::string& text, const std::string& path = "test.usda",
                                   const StageOptions& options = {}) {
    auto result = Stage::openFromString(text, path, options);
    if (const Error* error = std::get_if<Error>(&result)) {
        ADD_FAILURE() << "unexpected error: " << error->str();
        return nullptr;
    }
    return std::move(std::get<std::unique_ptr<Stage>>(result));
}

inline std::unique_ptr<Stage> openFile(const std::string& path, const StageOptions& options = {}) {
    auto result = Stage::open(path, options);
    if (const Error* error = std::get_if<Error>(&result)) {
        ADD_FAILURE() << "unexpected error: " << error->str();
        return nullptr;
    }
    return std::move(std::get<std::unique_ptr<Stage>>(result));
}

// Layers written to a folder of their own, by file name; the stage opened from "root.usda".
class LayerFiles {
public:
    explicit LayerFiles(const std::map<std::string, std::string>& files) {
        namespace fs = std::filesystem;
        dir_ = fs::temp_directory_path() / ("obscura_layers_" + std::to_string(counter_++) + "_" +
                                            std::to_string(::getpid()));  // the suite runs tests as parallel processes
        fs::create_directories(dir_);
        for (const auto& [name, text] : files) std::ofstream(dir_ / name) << text;
    }
    ~LayerFiles() { std::filesystem::remove_all(dir_); }
    std::unique_ptr<Stage> open(const StageOptions& options = {}) const {
        return openFile(path("root.usda"), options);
    }
    // Where the file `name` is (or would be) written.
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

private:
    static inline int counter_ = 0;
    std::filesystem::path dir_;
};

// The error opening `text` produces; an empty Error (and a test failure) if it opens.
inline Error openError(const std::string& text, const std::string& path = "scene.usda") {
    auto result = Stage::openFromString(text, path);
    if (const Error* error = std::get_if<Error>(&result)) return *error;
    ADD_FAILURE() << "expected an error for:\n" << text;
    return Error{};
}

// The default value of an attribute, failing the test when the prim, attribute or value is missing.
inline Value defaultOf(const Stage& stage, const std::string& primPath, const std::string& attr) {
    const Prim* prim = stage.find(primPath);
    if (!prim) {
        ADD_FAILURE() << "no prim " << primPath;
        return {};
    }
    const Attribute* attribute = prim->attribute(attr);
    if (!attribute || !attribute->defaultValue) {
        ADD_FAILURE() << "no default value for " << primPath << "." << attr;
        return {};
    }
    return *attribute->defaultValue;
}

}  // namespace obscura::usda::test
