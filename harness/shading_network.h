// UsdShade networks flattened for the delegate: the UsdUVTexture connected to a UsdPreviewSurface
// input (and the UsdPrimvarReader_float2 feeding the texture's st, through any UsdTransform2d) is
// served as the material's obscura:<input>:* attributes (schemas/material.json). UsdPreviewSurface spec:
// https://openusd.org/release/spec_usdpreviewsurface.html
#pragma once

#include "harness/texture_coordinates.h"
#include "harness/usda/stage.h"

#include <optional>
#include <variant>
#include <string>

namespace obscura::harness {

// Bad data in a shading network, where it was authored.
struct MaterialProblem {
    std::string message;
    usda::SourceLocation where;
};

// Where a connection leads as USD composes shading networks (UsdShadeConnectableAPI,
// UsdShadeUtils::GetValueProducingAttributes, first target): through NodeGraph and Material
// outputs to what they connect, through interface inputs (a NodeGraph's or Material's, or any
// connected input) to their own connection, until a Shader's output or an input that holds a value.
struct ConnectionSource {
    const usda::Prim* prim = nullptr;            // the shader, or the prim whose input holds the value
    std::string property;                        // "outputs:rgb", "inputs:baseColor"
    const usda::Attribute* attribute = nullptr;  // the input holding the value; null for a shader's output
};
// The source of `connected`'s connection (which it must have), or why there is none: a missing
// target, an unconnected NodeGraph output, a cycle.
std::variant<ConnectionSource, std::string> connectionSource(const usda::Stage& stage, const usda::Attribute& connected);
// The source when it is a Shader's output, else null (no connection, or one that ends in a value).
const usda::Prim* connectedShader(const usda::Stage& stage, const usda::Attribute& connected,
                                  std::string* output = nullptr);
// The attribute that holds an input's value: the input itself, or the interface input its
// connection leads to; null when it leads to a shader's output or nowhere.
const usda::Attribute* valueProducingAttribute(const usda::Stage& stage, const usda::Attribute& input);

// Whether a value the shader reads can change over time: one of its inputs, an input of a shader
// upstream of it, or an interface input they connect to is time-sampled.
bool isNetworkAnimated(const usda::Stage& stage, const usda::Prim& shader);

// A shader's info:id ("UsdPreviewSurface"), or "".
std::string shaderId(const usda::Prim& shader);

// The surface inputs the delegate reads textures for.
bool isTexturableInput(const std::string& input);  // "inputs:diffuseColor", ...

// The UsdUVTexture shader a surface input is connected to, with the output it reads (r, g, b, a
// or rgb); nullopt when the input is connected to anything else, or not connected.
struct TextureConnection {
    const usda::Prim* texture = nullptr;
    std::string channel;
};
std::optional<TextureConnection> textureConnection(const usda::Stage& stage, const usda::Attribute& input);

// Where a UsdUVTexture's inputs:st comes from: the UsdPrimvarReader_float2 at the end of a chain
// of UsdTransform2d shaders (none or several), and their transforms composed. A transform whose
// inputs are not finite is left out and reported in `problem`.
struct TextureCoordinates {
    std::optional<std::string> primvar;  // inputs:varname; nullopt without a reader
    StTransform transform;
    std::optional<MaterialProblem> problem;
};
TextureCoordinates textureCoordinates(const usda::Stage& stage, const usda::Prim& texture, double time);

// The value of "obscura:<input>:<field>" for a UsdPreviewSurface shader at `time`; nullopt when
// the input has no texture or the field is not authored (the schema default applies). Texture
// inputs connected to other inputs (a material's interface) take their value from there; a
// relative inputs:file is resolved against the folder of the layer that authored it. Bad data met
// on the way goes to `problem`.
std::optional<usda::Value> flattenedTextureAttribute(const usda::Stage& stage, const usda::Prim& surface,
                                                     const std::string& attribute, double time,
                                                     std::optional<MaterialProblem>* problem = nullptr);

// An asset path as an absolute path the plugin opens: relative paths are anchored to the folder of
// the layer that authored `attribute` (USD's ArDefaultResolver); in a USDZ package, to its folder
// in the package, giving a package path ("/dir/a.usdz[tex/b.png]", a UDIM set too) that the
// plugin reads from the archive in memory (assets/package_path.h).
std::string resolveAssetPath(const std::string& asset, const usda::Attribute& attribute);

// The primvar the shader's textures look up (inputs:varname of the UsdPrimvarReader_float2 that
// feeds the first textured input's inputs:st, directly or through UsdTransform2d), or "st".
std::string texturePrimvar(const usda::Stage& stage, const usda::Prim& surface);

// A UsdPrimvarReader connected to an input of a UsdPreviewSurface (UsdPreviewSurface spec,
// "Primvar Reading"): the prim's primvar named by inputs:varname is the input's value, and where
// the prim has none, the reader's inputs:fallback (unauthored: zero).
struct PrimvarRead {
    std::string primvar;                        // "displayColor", "Cd"
    const usda::Attribute* fallback = nullptr;  // the attribute holding inputs:fallback; null: zero
};
// The reader connected to `input` of `surface`, directly or through NodeGraph outputs, when it
// gives the input's type: three components (UsdPrimvarReader_float3, _normal, _point, _vector)
// for "inputs:diffuseColor", one (UsdPrimvarReader_float) for "inputs:opacity"; nullopt when the
// input reads none.
std::optional<PrimvarRead> primvarRead(const usda::Stage& stage, const usda::Prim& surface, const std::string& input);

}  // namespace obscura::harness
