// Text emission for USD's text format (.usda), limited to the syntax harness/usda's parser reads:
// indented prims, one property per line (every line ends with a newline), shortest round-trip numbers.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace obscura::harness::importer {

class UsdaWriter {
public:
    // "#usda 1.0" and the layer metadata, each item "key = value".
    explicit UsdaWriter(const std::vector<std::string>& layerMetadata);

    // `def <type> "<name>"` with optional metadata items ("prepend apiSchemas = [...]"); name must
    // be a valid identifier (see NameScope).
    void beginPrim(std::string_view type, std::string_view name, const std::vector<std::string>& metadata = {});
    void endPrim();
    // `<declaration> = <value>`, e.g. property("point3f[] points", "[(0, 0, 0)]").
    void property(std::string_view declaration, std::string_view value);
    // A per-vertex primvar or normals: the value followed by `( interpolation = "vertex" )`, with
    // `elementSize` values per vertex.
    void vertexProperty(std::string_view declaration, std::string_view value, size_t elementSize = 1);
    // A declaration without a value ("token outputs:surface").
    void declare(std::string_view declaration);
    // `<declaration>.timeSamples = { time: value, ... }`.
    void timeSamples(std::string_view declaration, const std::vector<std::pair<double, std::string>>& samples);

    std::string text() const { return text_; }

private:
    void line(std::string_view content);
    std::string text_;
    int depth_ = 0;
};

// Values as the parser reads them. Numbers must be finite: callers drop non-finite data first.
std::string number(float value);
std::string number(double value);
std::string tuple(std::initializer_list<float> components);
// A 4x4 matrix given row by row in USD's convention (row vectors, translation in the last row).
std::string matrix(const std::array<float, 16>& rowMajor);
// "[e0, e1, ...]" from `count` elements formatted by `element(i)`.
template <class Element>
std::string array(size_t count, Element element) {
    std::string out = "[";
    for (size_t i = 0; i < count; ++i) {
        if (i) out += ", ";
        out += element(i);
    }
    return out + "]";
}
std::string stringLiteral(std::string_view text);
std::string pathRef(std::string_view path);
// @path@, or @@@path@@@ when the path holds '@'; nullopt for paths with line breaks, which no
// asset path can hold.
std::optional<std::string> assetPath(std::string_view path);

// Prim names among siblings: source names made valid identifiers ([A-Za-z_][A-Za-z0-9_]*) and
// made unique by a numeric suffix.
class NameScope {
public:
    // The identifier for `name` (`fallback` when nothing of it survives), not yet used in this scope.
    std::string claim(std::string_view name, std::string_view fallback);

private:
    std::set<std::string> used_;
};

}  // namespace obscura::harness::importer
