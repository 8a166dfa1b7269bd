#include "harness/usda/materialx_layer.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace obscura::usda {
namespace {

// One XML element of the document with the attributes the translation reads.
struct Element {
    const xmlNode* node = nullptr;
    std::string category;  // the tag: "standard_surface", "nodegraph", "input"
    std::string name;
    std::string type;
    int line = 0;

    std::string attribute(const char* key) const {
        xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(key));
        if (!value) return {};
        std::string out(reinterpret_cast<const char*>(value));
        xmlFree(value);
        return out;
    }
    std::vector<Element> children() const {
        std::vector<Element> out;
        for (const xmlNode* child = node->children; child; child = child->next) {
            if (child->type != XML_ELEMENT_NODE) continue;
            Element e{child, reinterpret_cast<const char*>(child->name), {}, {}, int(xmlGetLineNo(child))};
            e.name = e.attribute("name");
            e.type = e.attribute("type");
            out.push_back(std::move(e));
        }
        return out;
    }
};

struct UsdType {
    const char* name;
    bool asset = false;
};

// MaterialX types as USD value types (MaterialX spec, "MaterialX Data Types"; usdMtlx's table).
std::optional<UsdType> usdTypeOf(const std::string& type) {
    static const std::map<std::string, UsdType> kTypes = {
        {"float", {"float"}},       {"integer", {"int"}},         {"boolean", {"bool"}},
        {"color3", {"color3f"}},    {"color4", {"color4f"}},      {"vector2", {"float2"}},
        {"vector3", {"float3"}},    {"vector4", {"float4"}},      {"matrix33", {"matrix3d"}},
        {"matrix44", {"matrix4d"}}, {"string", {"string"}},       {"filename", {"asset", true}},
        {"floatarray", {"float"}},  {"integerarray", {"int"}},    {"surfaceshader", {"token"}},
        {"displacementshader", {"token"}}, {"volumeshader", {"token"}}, {"material", {"token"}},
    };
    const auto it = kTypes.find(type);
    return it == kTypes.end() ? std::nullopt : std::optional(it->second);
}

const std::set<std::string> kStructuralCategories = {"input", "output", "parameter", "nodedef", "implementation",
                                                      "look", "lookgroup", "collection", "geominfo", "typedef",
                                                      "backdrop", "variantset", "propertyset", "materialassign"};

class Translator {
public:
    Translator(const Element& root, Layer& layer) : root_(root), layer_(layer) {
        for (const Element& e : root.children()) byName_.emplace(e.name, e);
    }

    void translate() {
        PrimSpec& top = child(layer_.pseudoRoot, "MaterialX", "Scope", root_.line);
        PrimSpec& materials = child(top, "Materials", "Scope", root_.line);
        for (const Element& e : root_.children())
            if (e.category == "surfacematerial" || (e.type == "material" && e.category != "nodedef"))
                translateMaterial(e, materials, "/MaterialX/Materials/" + e.name);
        layer_.metadata["defaultPrim"] = token("MaterialX");
    }

private:
    static Value token(std::string text) {
        Value v;
        v.typeName = "token";
        v.strings = {std::move(text)};
        return v;
    }

    SourceLocation at(int line) const { return SourceLocation{layer_.identifier, line, 0}; }

    PrimSpec& child(PrimSpec& parent, const std::string& name, const std::string& type, int line) {
        if (PrimSpec* existing = parent.childByName.count(name) ? parent.childByName[name] : nullptr) return *existing;
        auto spec = std::make_unique<PrimSpec>();
        spec->specifier = Specifier::Def;
        spec->typeName = type;
        spec->name = name;
        spec->where = at(line);
        PrimSpec& out = *spec;
        parent.childByName[name] = spec.get();
        parent.children.push_back(std::move(spec));
        return out;
    }

    void warn(int line, const std::string& message) {
        layer_.diagnostics.push_back(Diagnostic{"materialx:" + message, Warning{at(line), message}});
    }

    AttributeSpec& declare(PrimSpec& prim, const std::string& name, const std::string& mtlxType, int line) {
        AttributeSpec& attr = prim.attributes[name];
        const std::optional<UsdType> type = usdTypeOf(mtlxType);
        if (!type) warn(line, "MaterialX type '" + mtlxType + "' has no USD type; read as a token");
        const bool isArray = mtlxType.ends_with("array");
        attr.typeName = std::string(type ? type->name : "token") + (isArray ? "[]" : "");
        attr.type = findValueType(type ? type->name : "token");
        attr.isArray = isArray;
        attr.where = at(line);
        return attr;
    }

    // `fileprefix` applies to file names of the element and everything inside it.
    std::string filePrefix(const xmlNode* node) const {
        std::string prefix;
        for (const xmlNode* n = node; n && n->type == XML_ELEMENT_NODE; n = n->parent) {
            Element e{n, {}, {}, {}, 0};
            prefix = e.attribute("fileprefix") + prefix;
        }
        return prefix;
    }

    void setValue(AttributeSpec& attr, const Element& input, const std::string& text) {
        Value v;
        v.typeName = attr.type ? std::string(attr.type->name) : "token";
        v.isArray = attr.isArray;
        v.tupleSize = attr.type ? attr.type->tupleSize : 1;
        if (!attr.type || attr.type->scalar == ScalarKind::String || attr.type->scalar == ScalarKind::Token ||
            attr.type->scalar == ScalarKind::Asset) {
            v.strings = {attr.type && attr.type->scalar == ScalarKind::Asset ? filePrefix(input.node) + text : text};
        } else {
            std::string numbers = text;
            std::replace(numbers.begin(), numbers.end(), ',', ' ');
            std::istringstream in(numbers);
            std::string word;
            while (in >> word) {
                if (word == "true" || word == "false") {
                    v.numbers.edit().push_back(word == "true" ? 1.0 : 0.0);
                    continue;
                }
                char* end = nullptr;
                const double number = std::strtod(word.c_str(), &end);
                if (!end || *end) {
                    warn(input.line, "input '" + input.name + "': value \"" + text + "\" is not a " + input.type);
                    return;
                }
                v.numbers.edit().push_back(number);
            }
            if (!v.isArray && v.numbers.size() != size_t(v.tupleSize)) {
                warn(input.line, "input '" + input.name + "': value \"" + text + "\" is not a " + input.type);
                return;
            }
        }
        attr.defaultValue = std::move(v);
    }

    static std::string nodeId(const Element& node, const std::vector<Element>& inputs) {
        if (std::string nodedef = node.attribute("nodedef"); !nodedef.empty()) return nodedef;
        // MaterialX's standard library names mixed-type variants by the second argument's type:
        // multiply(color3, float) is ND_multiply_color3FA.
        for (const Element& input : inputs)
            if (input.name == "in2" && input.type == "float" && node.type != "float")
                return "ND_" + node.category + "_" + node.type + "FA";
        return "ND_" + node.category + "_" + node.type;
    }

    // A node as a Shader prim inside `parent`; `graph` is the node graph it sits in (at
    // `graphPath`), null at document level: connected nodes are then copied into the material.
    void translateNode(const Element& node, PrimSpec& parent, const Element* graph,
                       const std::string& graphPath, PrimSpec& material, const std::string& materialPath) {
        if (parent.childByName.count(node.name)) return;
        PrimSpec& shader = child(parent, node.name, "Shader", node.line);
        const std::vector<Element> children = node.children();
        std::vector<Element> inputs;
        for (const Element& c : children)
            if (c.category == "input" || c.category == "parameter") inputs.push_back(c);
        AttributeSpec& id = shader.attributes["info:id"];
        id.typeName = "uniform token";
        id.type = findValueType("token");
        id.isUniform = true;
        id.where = at(node.line);
        id.defaultValue = token(nodeId(node, inputs));
        for (const Element& input : inputs) translateInput(input, shader, graph, graphPath, material, materialPath);
        bool outputs = false;
        for (const Element& c : children)
            if (c.category == "output") {
                declare(shader, "outputs:" + c.name, c.type, c.line);
                outputs = true;
            }
        if (!outputs)
            declare(shader, node.type == "surfaceshader" ? "outputs:surface" : "outputs:out", node.type, node.line);
    }

    void translateInput(const Element& input, PrimSpec& prim, const Element* graph,
                        const std::string& graphPath, PrimSpec& material, const std::string& materialPath) {
        AttributeSpec& attr = declare(prim, "inputs:" + input.name, input.type, input.line);
        if (xmlHasProp(input.node, reinterpret_cast<const xmlChar*>("value"))) setValue(attr, input, input.attribute("value"));
        if (std::string space = input.attribute("colorspace"); !space.empty()) attr.metadata["colorSpace"] = token(space);
        std::string target;
        const std::string output = input.attribute("output");
        if (std::string nodeName = input.attribute("nodename"); !nodeName.empty()) {
            target = connectNode(nodeName, output, input, graph, graphPath, material, materialPath);
        } else if (std::string graphName = input.attribute("nodegraph"); !graphName.empty()) {
            target = connectGraph(graphName, output, input, material, materialPath);
        } else if (std::string interface = input.attribute("interfacename"); !interface.empty() && graph) {
            target = graphPath + ".inputs:" + interface;
        }
        if (!target.empty()) attr.connections.set(ListOpKind::Explicit, {target});
    }

    std::string connectNode(const std::string& nodeName, const std::string& output, const Element& input,
                            const Element* graph, const std::string& graphPath, PrimSpec& material,
                            const std::string& materialPath) {
        const std::string port = ".outputs:" + (output.empty() ? std::string("out") : output);
        if (graph) {
            for (const Element& sibling : graph->children())
                if (sibling.name == nodeName) return graphPath + "/" + nodeName + port;
            warn(input.line, "input '" + input.name + "' connects to node '" + nodeName + "', which graph '" +
                                 graph->name + "' does not have");
            return {};
        }
        const auto node = byName_.find(nodeName);
        if (node == byName_.end() || kStructuralCategories.count(node->second.category) ||
            node->second.category == "nodegraph") {
            warn(input.line, "input '" + input.name + "' connects to node '" + nodeName + "', which the document does not have");
            return {};
        }
        translateNode(node->second, material, nullptr, {}, material, materialPath);
        const std::string port2 = node->second.type == "surfaceshader" ? ".outputs:surface" : port;
        return materialPath + "/" + nodeName + port2;
    }

    std::string connectGraph(const std::string& graphName, const std::string& output, const Element& input,
                             PrimSpec& material, const std::string& materialPath) {
        const auto graph = byName_.find(graphName);
        if (graph == byName_.end() || graph->second.category != "nodegraph") {
            warn(input.line, "input '" + input.name + "' connects to node graph '" + graphName +
                                 "', which the document does not have");
            return {};
        }
        translateGraph(graph->second, material, materialPath);
        return materialPath + "/" + graphName + ".outputs:" + (output.empty() ? std::string("out") : output);
    }

    void translateGraph(const Element& graph, PrimSpec& material, const std::string& materialPath) {
        if (material.childByName.count(graph.name)) return;
        PrimSpec& prim = child(material, graph.name, "NodeGraph", graph.line);
        const std::string path = materialPath + "/" + graph.name;
        for (const Element& e : graph.children()) {
            if (e.category == "input") {
                translateInput(e, prim, nullptr, {}, material, materialPath);
            } else if (e.category == "output") {
                AttributeSpec& attr = declare(prim, "outputs:" + e.name, e.type, e.line);
                if (std::string nodeName = e.attribute("nodename"); !nodeName.empty())
                    attr.connections.set(ListOpKind::Explicit,
                                         {path + "/" + nodeName + ".outputs:" +
                                          (e.attribute("output").empty() ? std::string("out") : e.attribute("output"))});
            } else if (!kStructuralCategories.count(e.category)) {
                translateNode(e, prim, &graph, path, material, materialPath);
            }
        }
    }

    void translateMaterial(const Element& material, PrimSpec& materials, const std::string& path) {
        PrimSpec& prim = child(materials, material.name, "Material", material.line);
        for (const Element& input : material.children()) {
            if (input.category != "input") continue;
            const std::string shader = input.attribute("nodename");
            const auto node = byName_.find(shader);
            if (input.name != "surfaceshader") continue;  // XXX: displacement and volume shaders are not drawn
            if (node == byName_.end()) {
                warn(input.line, "material '" + material.name + "': surfaceshader '" + shader + "' is not in the document");
                continue;
            }
            translateNode(node->second, prim, nullptr, {}, prim, path);
            AttributeSpec& surface = declare(prim, "outputs:mtlx:surface", "surfaceshader", input.line);
            surface.connections.set(ListOpKind::Explicit, {path + "/" + shader + ".outputs:surface"});
        }
    }

    const Element& root_;
    Layer& layer_;
    std::map<std::string, Element> byName_;
};

}  // namespace

bool isMaterialXDocument(const std::string& identifier) {
    if (identifier.size() < 5) return false;
    std::string extension = identifier.substr(identifier.size() - 5);
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".mtlx";
}

std::variant<std::unique_ptr<Layer>, Error> readMaterialXLayer(std::string_view bytes, const std::string& identifier) {
    // The first error is where the document goes wrong; later ones follow from it.
    struct FirstError {
        bool seen = false;
        int line = 0, column = 0;
        std::string message;
    } first;
    xmlSetStructuredErrorFunc(&first, [](void* user, xmlErrorPtr error) {
        auto* out = static_cast<FirstError*>(user);
        if (out->seen || !error) return;
        *out = FirstError{true, error->line, error->int2, error->message ? error->message : ""};
    });
    // No network access and no entity expansion: a document may not reach outside itself.
    xmlDoc* doc = xmlReadMemory(bytes.data(), int(std::min(bytes.size(), size_t(INT32_MAX))), identifier.c_str(), nullptr,
                                XML_PARSE_NONET | XML_PARSE_NOWARNING);
    xmlSetStructuredErrorFunc(nullptr, nullptr);
    if (!doc) {
        std::string message = first.seen && !first.message.empty() ? first.message : "it cannot be parsed";
        while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
        return Error{SourceLocation{identifier, first.line, first.column}, "not well-formed XML: " + message};
    }
    const xmlNode* rootNode = xmlDocGetRootElement(doc);
    if (!rootNode || std::string(reinterpret_cast<const char*>(rootNode->name)) != "materialx") {
        xmlFreeDoc(doc);
        return Error{SourceLocation{identifier, 1, 0}, "not a MaterialX document: its root element is not <materialx>"};
    }
    auto layer = std::make_unique<Layer>();
    layer->identifier = identifier;
    Element root{rootNode, "materialx", {}, {}, int(xmlGetLineNo(rootNode))};
    Translator(root, *layer).translate();
    xmlFreeDoc(doc);
    return layer;
}

}  // namespace obscura::usda
