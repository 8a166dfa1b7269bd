// MaterialX surface shaders in UsdShade (Shader prims whose info:id is a MaterialX node
// definition, "ND_...", as usdMtlx and DCCs author them) mapped onto Obscura's material model, the
// inputs of UsdPreviewSurface (schemas/material.json): Standard Surface, UsdPreviewSurface's own
// node definition, glTF PBR and OpenPBR surfaces, each input with its model's default. Networks
// feeding an input are folded where the model can hold them: ND_image_* (and ND_tiledimage_*,
// its uvtiling and uvoffset an affine map of the texture coordinates)
// become the input's texture (file, colour space, address modes, ND_texcoord/ND_geompropvalue
// primvar), ND_geompropvalue_color3/_vector3/_float on the base colour (times a constant) or on the
// opacity a primvar read (obscura:diffuseColor:primvar, obscura:opacity:primvar), ND_normalmap a normal map (scale 2, bias -1, as UsdPreviewSurface's normal maps),
// ND_multiply/ND_add/ND_subtract/ND_mix with constants a texture's scale and bias or a constant
// folded, ND_extract a channel, ND_constant/ND_dot/ND_convert pass through. What cannot map is
// reported (one problem per node) and its input keeps the model's default; a surface of another
// kind is drawn with its base colour.
// MaterialX node definitions: https://materialx.org/assets/MaterialX.v1.38.Spec.pdf
#pragma once

#include "harness/shading_network.h"
#include "harness/texture_coordinates.h"
#include "harness/usda/stage.h"

#include <map>
#include <string>
#include <vector>

namespace obscura::harness {

// A texture on one of the material model's inputs, as a mapping serves it (obscura:<input>:*).
struct MappedTexture {
    std::string file;                       // resolved
    std::string colorSpace = "raw";         // "sRGB" or "raw"
    std::string wrapS = "repeat", wrapT = "repeat";
    std::string st = "st";                  // the primvar it reads
    StTransform transform;                  // of the texture coordinates
    std::string channel = "rgb";
};

struct MaterialXMapping {
    // Values by the delegate's attribute names: "inputs:diffuseColor", "obscura:normal:file", ...;
    // an attribute left out takes the schema default.
    std::map<std::string, usda::Value> values;
    std::string stPrimvar = "st";  // the primvar the textures read
    // ND_geompropvalue on the base colour or opacity, by the input read ("inputs:diffuseColor",
    // "inputs:opacity"): the host serves the primvar as the bound prims' displayColor
    // (displayOpacity), as for a UsdPrimvarReader.
    std::map<std::string, PrimvarRead> primvarReads;
    std::vector<MaterialProblem> problems;
};

// One value of `type` ("float3") holding `n`, as a mapping serves a constant.
usda::Value numbersValue(const char* type, std::vector<double> n);

// `texture` times `scale` plus `bias` (three components, alpha 1 and 0 added) as the values of
// `usdInput` ("diffuseColor"); the first texture's primvar becomes the mapping's stPrimvar.
void storeTexture(MaterialXMapping& out, const std::string& usdInput, const MappedTexture& texture,
                  std::vector<double> scale, std::vector<double> bias);

// Whether a shader id names a MaterialX node definition this mapping reads as a surface.
bool isMaterialXShader(const std::string& shaderId);

// `surface`'s inputs at `time`, mapped.
MaterialXMapping mapMaterialXSurface(const usda::Stage& stage, const usda::Prim& surface, double time);

}  // namespace obscura::harness
