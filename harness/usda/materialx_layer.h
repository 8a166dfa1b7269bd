// A MaterialX document (.mtlx) read as a USD layer, as OpenUSD's usdMtlx file format plugin
// presents one to composition: every surfacematerial becomes a UsdShade Material under
// /MaterialX/Materials (the layer's default prim is /MaterialX), holding the shader nodes and node
// graphs it uses as Shader and NodeGraph prims (each node's info:id its nodedef, "ND_<category>_<type>"
// unless the document names one), MaterialX inputs as `inputs:` attributes (values, file names as
// asset paths relative to the document, colorspace as the `colorSpace` metadata) and MaterialX
// connections (nodename, nodegraph/output, interfacename) as UsdShade connections. The Material's
// surface is `outputs:mtlx:surface`, MaterialX's render context.
// Specification: https://materialx.org/assets/MaterialX.v1.38.Spec.pdf (Elements, Node graphs).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <variant>

#include "harness/usda/layer.h"

namespace obscura::usda {

// Whether `identifier` names a MaterialX document (by its extension, as USD's file formats go).
bool isMaterialXDocument(const std::string& identifier);

// The layer, or an error naming the line of the document where it is malformed.
std::variant<std::unique_ptr<Layer>, Error> readMaterialXLayer(std::string_view bytes, const std::string& identifier);

}  // namespace obscura::usda
