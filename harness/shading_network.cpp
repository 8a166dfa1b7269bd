#include "harness/shading_network.h"

#include "assets/package_path.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

namespace obscura::harness {
namespace {

constexpr std::array<std::string_view, 7> kTexturableInputs = {
    "inputs:diffuseColor", "inputs:emissiveColor", "inputs:roughness", "inputs:metallic",
    "inputs:opacity",      "inputs:normal",        "inputs:occlusion"};
constexpr std::array<std::string_view, 5> kTextureOutputs = {"r", "g", "b", "a", "rgb"};
// Connections between inputs are followed this far (a cycle is an authoring error).
constexpr int kMaxConnectionDepth = 16;

// "/Material/Texture.outputs:rgb" -> the prim and the property. Prim names never hold a '.'.
std::pair<std::string, std::string> splitPropertyPath(const std::string& path) {
    const auto dot = path.find('.');
    if (dot == std::string::npos) return {path, ""};
    return {path.substr(0, dot), path.substr(dot + 1)};
}

// The value of a shader input at `time`, following its connection to another input (a Material's
// or NodeGraph's interface) when it has one; `from` receives the attribute that held the value.
std::optional<usda::Value> evaluateInput(const usda::Stage& stage, const usda::Prim& prim, const std::string& name,
                                         double time, const usda::Attribute** from = nullptr) {
    const usda::Attribute* input = prim.attribute(name);
    const usda::Attribute* attribute = input ? valueProducingAttribute(stage, *input) : nullptr;
    if (!attribute) return std::nullopt;
    auto value = attribute->evaluate(time);
    if (!value || value->empty()) return std::nullopt;
    if (from) *from = attribute;
    return value;
}

usda::Value tokenValue(std::string text) {
    usda::Value value;
    value.typeName = "token";
    value.strings = {std::move(text)};
    return value;
}

usda::Value float3Value(const std::array<double, 3>& row) {
    usda::Value value;
    value.typeName = "float3";
    value.tupleSize = 3;
    value.numbers = std::vector<double>(row.begin(), row.end());
    return value;
}

// A UsdTransform2d's input of `size` numbers at `time`, or its default; nullopt when what is
// authored is not `size` finite numbers (then `problem` says so).
std::optional<std::vector<double>> transformInput(const usda::Stage& stage, const usda::Prim& shader,
                                                  const char* name, std::vector<double> fallback, double time,
                                                  std::optional<MaterialProblem>& problem) {
    const usda::Attribute* from = nullptr;
    auto value = evaluateInput(stage, shader, name, time, &from);
    if (!value) return fallback;
    const bool finite = std::all_of(value->numbers.begin(), value->numbers.end(), [](double v) { return std::isfinite(v); });
    if (value->numbers.size() == fallback.size() && finite) return value->numbers;
    if (!problem)
        problem = MaterialProblem{shader.path + "." + name + " must be " + std::to_string(fallback.size()) +
                                      " finite number" + (fallback.size() > 1 ? "s" : "") + "; the transform is ignored",
                                  from->where};
    return std::nullopt;
}

}  // namespace

TextureCoordinates textureCoordinates(const usda::Stage& stage, const usda::Prim& texture, double time) {
    TextureCoordinates out;
    const usda::Attribute* st = texture.attribute("inputs:st");
    // Each UsdTransform2d met on the way to the reader applies before those already met.
    for (int depth = 0; st && st->connection && depth < kMaxConnectionDepth; ++depth) {
        const usda::Prim* shader = connectedShader(stage, *st);
        if (!shader) break;
        const std::string id = shaderId(*shader);
        if (id == "UsdPrimvarReader_float2") {
            // varname names a primvar, not something that varies over time.
            auto name = evaluateInput(stage, *shader, "inputs:varname", 0.0);
            if (name && !name->strings.empty() && !name->strings[0].empty()) out.primvar = name->strings[0];
            break;
        }
        if (id != "UsdTransform2d") break;
        auto scale = transformInput(stage, *shader, "inputs:scale", {1.0, 1.0}, time, out.problem);
        auto rotation = transformInput(stage, *shader, "inputs:rotation", {0.0}, time, out.problem);
        auto translation = transformInput(stage, *shader, "inputs:translation", {0.0, 0.0}, time, out.problem);
        if (scale && rotation && translation)
            out.transform = compose(out.transform, transform2d({(*scale)[0], (*scale)[1]}, (*rotation)[0],
                                                               {(*translation)[0], (*translation)[1]}));
        st = shader->attribute("inputs:in");
    }
    return out;
}

std::variant<ConnectionSource, std::string> connectionSource(const usda::Stage& stage, const usda::Attribute& connected) {
    const usda::Attribute* attribute = &connected;
    for (int depth = 0; depth < kMaxConnectionDepth; ++depth) {
        auto [sourcePath, property] = splitPropertyPath(*attribute->connection);
        const usda::Prim* source = stage.find(sourcePath);
        if (!source) return "its connection target <" + *attribute->connection + "> does not exist";
        const bool isOutput = property.rfind("outputs:", 0) == 0;
        if (!isOutput && property.rfind("inputs:", 0) != 0)
            return "its connection target <" + *attribute->connection + "> is neither an input nor an output";
        // A shader's output is where a value is computed.
        if (isOutput && source->typeName == "Shader") return ConnectionSource{source, property, nullptr};
        const usda::Attribute* next = source->attribute(property);
        if (!next) return "its connection target <" + *attribute->connection + "> does not exist";
        // A NodeGraph's (or Material's) output passes on what it connects to inside.
        if (isOutput && !next->connection) return "<" + *attribute->connection + "> is an output connected to nothing";
        // An input without a connection of its own holds the value.
        if (!next->connection) return ConnectionSource{source, property, next};
        attribute = next;
    }
    return "its connections form a cycle (or a chain longer than " + std::to_string(kMaxConnectionDepth) + ")";
}

const usda::Prim* connectedShader(const usda::Stage& stage, const usda::Attribute& connected, std::string* output) {
    if (!connected.connection) return nullptr;
    auto source = connectionSource(stage, connected);
    auto* found = std::get_if<ConnectionSource>(&source);
    if (!found || found->attribute) return nullptr;
    if (output) *output = found->property;
    return found->prim;
}

const usda::Attribute* valueProducingAttribute(const usda::Stage& stage, const usda::Attribute& input) {
    if (!input.connection) return &input;
    auto source = connectionSource(stage, input);
    auto* found = std::get_if<ConnectionSource>(&source);
    return found ? found->attribute : nullptr;
}

bool isNetworkAnimated(const usda::Stage& stage, const usda::Prim& shader) {
    std::set<const usda::Prim*> seen;
    std::vector<const usda::Prim*> pending = {&shader};
    while (!pending.empty()) {
        const usda::Prim* prim = pending.back();
        pending.pop_back();
        if (!seen.insert(prim).second) continue;
        for (const auto& [name, attribute] : prim->attributes) {
            if (name.rfind("inputs:", 0) != 0) continue;
            if (!attribute.connection) {
                if (attribute.isAnimated()) return true;
                continue;
            }
            const auto source = connectionSource(stage, attribute);
            const ConnectionSource* found = std::get_if<ConnectionSource>(&source);
            if (!found) continue;  // a broken connection reads no value; it is reported where it is mapped
            if (!found->attribute) pending.push_back(found->prim);  // a shader's output: its own inputs
            else if (found->attribute->isAnimated()) return true;
        }
    }
    return false;
}

std::string shaderId(const usda::Prim& prim) {
    const usda::Attribute* id = prim.attribute("info:id");
    auto value = id ? id->evaluate(0) : std::nullopt;
    return value && !value->strings.empty() ? value->strings[0] : "";
}

bool isTexturableInput(const std::string& input) {
    for (std::string_view name : kTexturableInputs)
        if (name == input) return true;
    return false;
}

std::optional<TextureConnection> textureConnection(const usda::Stage& stage, const usda::Attribute& input) {
    std::string output;
    const usda::Prim* shader = connectedShader(stage, input, &output);
    if (!shader || shaderId(*shader) != "UsdUVTexture") return std::nullopt;
    std::string channel = output.substr(8);
    for (std::string_view known : kTextureOutputs)
        if (known == channel) return TextureConnection{shader, channel};
    return std::nullopt;
}

std::optional<usda::Value> flattenedTextureAttribute(const usda::Stage& stage, const usda::Prim& surface,
                                                     const std::string& attribute, double time,
                                                     std::optional<MaterialProblem>* problem) {
    constexpr std::string_view kPrefix = "obscura:";
    const auto lastColon = attribute.rfind(':');
    if (attribute.rfind(kPrefix, 0) != 0 || lastColon <= kPrefix.size()) return std::nullopt;
    const std::string input = "inputs:" + attribute.substr(kPrefix.size(), lastColon - kPrefix.size());
    const std::string field = attribute.substr(lastColon + 1);
    const usda::Attribute* connected = isTexturableInput(input) ? surface.attribute(input) : nullptr;
    auto connection = connected ? textureConnection(stage, *connected) : std::nullopt;
    if (!connection) return std::nullopt;
    const usda::Prim& texture = *connection->texture;

    if (field == "channel") return tokenValue(connection->channel);
    if (field == "st") {
        auto primvar = textureCoordinates(stage, texture, time).primvar;
        return primvar ? std::optional(tokenValue(*primvar)) : std::nullopt;
    }
    if (field == "transformS" || field == "transformT") {
        TextureCoordinates coordinates = textureCoordinates(stage, texture, time);
        if (problem) *problem = coordinates.problem;
        return float3Value(field == "transformS" ? coordinates.transform.s : coordinates.transform.t);
    }
    if (field == "file") {
        const usda::Attribute* from = nullptr;
        auto asset = evaluateInput(stage, texture, "inputs:file", time, &from);
        if (!asset || asset->strings.empty() || asset->strings[0].empty()) return std::nullopt;
        return tokenValue(resolveAssetPath(asset->strings[0], *from));
    }
    if (field == "wrapS" || field == "wrapT" || field == "scale" || field == "bias" || field == "sourceColorSpace")
        return evaluateInput(stage, texture, "inputs:" + field, time);
    return std::nullopt;
}

std::string resolveAssetPath(const std::string& asset, const usda::Attribute& attribute) {
    return assets::absoluteAssetPath(assets::anchorAssetPath(asset, attribute.where.file));
}

std::string texturePrimvar(const usda::Stage& stage, const usda::Prim& surface) {
    for (std::string_view input : kTexturableInputs) {
        const usda::Attribute* connected = surface.attribute(std::string(input));
        auto connection = connected ? textureConnection(stage, *connected) : std::nullopt;
        if (connection) return textureCoordinates(stage, *connection->texture, 0.0).primvar.value_or("st");
    }
    return "st";
}

std::optional<PrimvarRead> primvarRead(const usda::Stage& stage, const usda::Prim& surface, const std::string& input) {
    static const std::set<std::string, std::less<>> kColorReaders = {
        "UsdPrimvarReader_float3", "UsdPrimvarReader_normal", "UsdPrimvarReader_point", "UsdPrimvarReader_vector"};
    static const std::set<std::string, std::less<>> kScalarReaders = {"UsdPrimvarReader_float"};
    if (input != "inputs:diffuseColor" && input != "inputs:opacity") return std::nullopt;
    const auto& readers = input == "inputs:diffuseColor" ? kColorReaders : kScalarReaders;
    const usda::Attribute* connected = surface.attribute(input);
    const usda::Prim* reader = connected ? connectedShader(stage, *connected) : nullptr;
    if (!reader || !readers.count(shaderId(*reader))) return std::nullopt;
    // varname names a primvar, not something that varies over time.
    auto name = evaluateInput(stage, *reader, "inputs:varname", 0.0);
    if (!name || name->strings.empty() || name->strings[0].empty()) return std::nullopt;
    const usda::Attribute* fallback = reader->attribute("inputs:fallback");
    return PrimvarRead{name->strings[0], fallback ? valueProducingAttribute(stage, *fallback) : nullptr};
}

}  // namespace obscura::harness
