// Build-time tool: reads the prim schemas (schemas/*.json), validates them and writes the C++
// tables behind schemas/schema.h and the Markdown reference docs/schemas.md.
//
//   generate_schema_tables <out tables.cpp> <out schemas.md> <schema.json>...
//
// Prims keep the order of the arguments. Every problem is reported as "file: attribute: reason"
// on stderr and makes the tool exit with 1 without writing anything, so a broken schema fails
// the build instead of producing tables that disagree with the docs.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// ------------------------------------------------------------------------------------------
// The schema language
// ------------------------------------------------------------------------------------------

enum class Kind { Bool, Number, Token, Path, Array };

struct TypeInfo {
    const char* name;         // spelling in the JSON files
    const char* enumerator;   // obscura::schema::AttrType enumerator
    Kind kind;
    int components;           // numbers per default value (Number only)
    bool integral;            // defaults must be whole numbers
};

constexpr std::array kTypes{
    TypeInfo{"bool", "Bool", Kind::Bool, 1, true},
    TypeInfo{"int", "Int", Kind::Number, 1, true},
    TypeInfo{"float", "Float", Kind::Number, 1, false},
    TypeInfo{"double", "Double", Kind::Number, 1, false},
    TypeInfo{"float2", "Float2", Kind::Number, 2, false},
    TypeInfo{"float3", "Float3", Kind::Number, 3, false},
    TypeInfo{"float4", "Float4", Kind::Number, 4, false},
    TypeInfo{"int2", "Int2", Kind::Number, 2, true},
    TypeInfo{"matrix4d", "Matrix4d", Kind::Number, 16, false},
    TypeInfo{"token", "Token", Kind::Token, 0, false},
    TypeInfo{"path", "Path", Kind::Path, 0, false},
    TypeInfo{"int[]", "IntArray", Kind::Array, 0, true},
    TypeInfo{"float[]", "FloatArray", Kind::Array, 0, false},
    TypeInfo{"float2[]", "Float2Array", Kind::Array, 0, false},
    TypeInfo{"float3[]", "Float3Array", Kind::Array, 0, false},
    TypeInfo{"float4[]", "Float4Array", Kind::Array, 0, false},
    TypeInfo{"path[]", "PathArray", Kind::Array, 0, false},
};

// Dirty-bit names of the JSON files and the OBSCURA_DIRTY_* macros they stand for.
const std::map<std::string, std::string> kDirtyBits{
    {"transform", "OBSCURA_DIRTY_TRANSFORM"},   {"points", "OBSCURA_DIRTY_POINTS"},
    {"topology", "OBSCURA_DIRTY_TOPOLOGY"},     {"normals", "OBSCURA_DIRTY_NORMALS"},
    {"primvar", "OBSCURA_DIRTY_PRIMVAR"},       {"materialId", "OBSCURA_DIRTY_MATERIAL_ID"},
    {"params", "OBSCURA_DIRTY_PARAMS"},         {"visibility", "OBSCURA_DIRTY_VISIBILITY"},
    {"doubleSided", "OBSCURA_DIRTY_DOUBLE_SIDED"},
};

const std::set<std::string> kCategories{"rprim", "sprim", "bprim"};
const std::set<std::string> kInterpolations{"constant", "uniform", "varying", "vertex", "faceVarying"};

struct Attribute {
    std::string name;
    std::string usdType;
    const TypeInfo* type = nullptr;
    bool hasDefault = false;
    std::vector<double> defaultNumbers;   // Bool and Number defaults
    std::string defaultString;            // Token and Path defaults
    std::string units;                    // "" = no unit
    bool timeSampled = false;
    std::string dirtyBit;
    std::optional<std::string> interpolation;
    std::vector<std::string> tokens;
    std::string doc;
};

struct Prim {
    std::string name;
    std::string usdType;
    std::string category;
    std::string doc;
    std::vector<Attribute> attributes;
};

// ------------------------------------------------------------------------------------------
// Reading and validation
// ------------------------------------------------------------------------------------------

// A problem in one schema; the caller adds the file and attribute it belongs to.
struct SchemaError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& message) { throw SchemaError(message); }

// Keys must be among `required` and `optional`, and every required key present: a misspelt
// key ("dirtybit") would otherwise be silently ignored.
void checkKeys(const json& object, std::initializer_list<const char*> required,
               std::initializer_list<const char*> optional) {
    if (!object.is_object()) fail("expected a JSON object, got " + object.dump());
    for (const char* key : required)
        if (!object.contains(key)) fail(std::string("missing key \"") + key + "\"");
    for (const auto& item : object.items()) {
        auto matches = [&](const char* key) { return item.key() == key; };
        if (std::none_of(required.begin(), required.end(), matches) &&
            std::none_of(optional.begin(), optional.end(), matches))
            fail("unknown key \"" + item.key() + "\"");
    }
}

std::string getString(const json& object, const char* key, bool allowEmpty = false) {
    const json& value = object.at(key);
    if (!value.is_string()) fail(std::string("\"") + key + "\" must be a string, got " + value.dump());
    std::string text = value.get<std::string>();
    if (text.empty() && !allowEmpty) fail(std::string("\"") + key + "\" must not be empty");
    return text;
}

const TypeInfo& parseType(const json& value) {
    if (value.is_string())
        for (const TypeInfo& type : kTypes)
            if (value.get<std::string>() == type.name) return type;
    std::string known;
    for (const TypeInfo& type : kTypes) known += std::string(known.empty() ? "" : ", ") + type.name;
    fail("unknown type " + value.dump() + " (one of: " + known + ")");
}

double parseNumber(const json& value, const TypeInfo& type) {
    if (type.integral) {
        if (!value.is_number_integer()) fail("default " + value.dump() + " is not a whole number");
        const auto number = value.get<int64_t>();
        if (number < std::numeric_limits<int32_t>::min() || number > std::numeric_limits<int32_t>::max())
            fail("default " + value.dump() + " does not fit in 32 bits");
        return static_cast<double>(number);
    }
    if (!value.is_number()) fail("default " + value.dump() + " is not a number");
    return value.get<double>();
}

// A Number default: a scalar for one component, [x, y...] for vectors, 4 rows of 4 for matrix4d.
std::vector<double> parseNumbers(const json& value, const TypeInfo& type) {
    const std::string shape = type.components == 1  ? "a number"
                              : type.components == 16 ? "4 rows of 4 numbers"
                                                      : "an array of " + std::to_string(type.components) + " numbers";
    auto wrongShape = [&] { fail("default of a " + std::string(type.name) + " must be " + shape + ", got " + value.dump()); };
    if (type.components == 1) {
        if (!value.is_number()) wrongShape();
        return {parseNumber(value, type)};
    }
    // A matrix is written as rows for readability; flatten them row-major like GfMatrix4d.
    std::vector<json> elements;
    if (type.components == 16) {
        if (!value.is_array() || value.size() != 4) wrongShape();
        for (const json& row : value) {
            if (!row.is_array() || row.size() != 4) wrongShape();
            elements.insert(elements.end(), row.begin(), row.end());
        }
    } else {
        if (!value.is_array() || value.size() != static_cast<size_t>(type.components)) wrongShape();
        elements.assign(value.begin(), value.end());
    }
    std::vector<double> numbers;
    for (const json& element : elements) {
        if (!element.is_number()) wrongShape();
        numbers.push_back(parseNumber(element, type));
    }
    return numbers;
}

void parseDefault(const json& value, Attribute& attribute) {
    const TypeInfo& type = *attribute.type;
    if (value.is_null()) return;   // no default: the attribute is absent until authored
    attribute.hasDefault = true;
    switch (type.kind) {
    case Kind::Bool:
        if (!value.is_boolean()) fail("default of a bool must be true or false, got " + value.dump());
        attribute.defaultNumbers = {value.get<bool>() ? 1.0 : 0.0};
        return;
    case Kind::Number:
        attribute.defaultNumbers = parseNumbers(value, type);
        return;
    case Kind::Token:
        if (!value.is_string()) fail("default of a token must be a string, got " + value.dump());
        attribute.defaultString = value.get<std::string>();
        return;
    case Kind::Path:
        if (!value.is_string() || value.get<std::string>().rfind('/', 0) != 0)
            fail("default of a path must be an absolute path string, got " + value.dump());
        attribute.defaultString = value.get<std::string>();
        return;
    case Kind::Array:
        // An unauthored array is simply absent (USD's fallback is an empty array).
        fail("default of an array type (" + std::string(type.name) + ") must be null, got " + value.dump());
    }
}

void parseTokens(const json& object, Attribute& attribute) {
    if (!object.contains("tokens")) return;
    if (attribute.type->kind != Kind::Token) fail("\"tokens\" is only allowed on token attributes");
    const json& tokens = object.at("tokens");
    if (!tokens.is_array() || tokens.empty()) fail("\"tokens\" must be a non-empty array of strings, got " + tokens.dump());
    for (const json& token : tokens) {
        if (!token.is_string() || token.get<std::string>().empty())
            fail("\"tokens\" must be a non-empty array of strings, got " + tokens.dump());
        if (std::find(attribute.tokens.begin(), attribute.tokens.end(), token.get<std::string>()) != attribute.tokens.end())
            fail("token " + token.dump() + " is listed twice");
        attribute.tokens.push_back(token.get<std::string>());
    }
    if (attribute.hasDefault &&
        std::find(attribute.tokens.begin(), attribute.tokens.end(), attribute.defaultString) == attribute.tokens.end())
        fail("default \"" + attribute.defaultString + "\" is not one of the allowed tokens");
}

Attribute parseAttribute(const json& object) {
    checkKeys(object, {"name", "usdType", "type", "default", "units", "timeSampled", "dirtyBit", "doc"},
              {"interpolation", "tokens"});
    Attribute attribute;
    attribute.name = getString(object, "name");
    attribute.usdType = getString(object, "usdType");
    attribute.type = &parseType(object.at("type"));
    parseDefault(object.at("default"), attribute);
    parseTokens(object, attribute);

    const json& units = object.at("units");
    if (!units.is_null()) attribute.units = getString(object, "units");

    if (!object.at("timeSampled").is_boolean())
        fail("\"timeSampled\" must be true or false, got " + object.at("timeSampled").dump());
    attribute.timeSampled = object.at("timeSampled").get<bool>();

    const json& dirtyBit = object.at("dirtyBit");
    if (!dirtyBit.is_string() || !kDirtyBits.contains(dirtyBit.get<std::string>())) {
        std::string known;
        for (const auto& [name, macro] : kDirtyBits) known += (known.empty() ? "" : ", ") + name;
        fail("unknown dirty bit " + dirtyBit.dump() + " (one of: " + known + ")");
    }
    attribute.dirtyBit = dirtyBit.get<std::string>();

    if (object.contains("interpolation") && !object.at("interpolation").is_null()) {
        const json& interpolation = object.at("interpolation");
        if (attribute.type->kind != Kind::Array) fail("\"interpolation\" is only allowed on array attributes");
        if (!interpolation.is_string() || !kInterpolations.contains(interpolation.get<std::string>()))
            fail("unknown interpolation " + interpolation.dump());
        attribute.interpolation = interpolation.get<std::string>();
    }
    attribute.doc = getString(object, "doc");
    return attribute;
}

bool isIdentifier(const std::string& name) {
    return !name.empty() && std::isalpha(static_cast<unsigned char>(name[0])) &&
           std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
}

// Reads one schema file; problems are appended to `errors` as "file: attribute: reason".
std::optional<Prim> readPrim(const fs::path& file, std::vector<std::string>& errors) {
    const std::string where = file.filename().string();
    std::ifstream stream(file);
    if (!stream) {
        errors.push_back(where + ": cannot open " + file.string());
        return std::nullopt;
    }
    json document;
    try {
        document = json::parse(stream);
    } catch (const json::parse_error& error) {
        errors.push_back(where + ": " + error.what());
        return std::nullopt;
    }

    Prim prim;
    const size_t errorsBefore = errors.size();
    try {
        checkKeys(document, {"name", "usdType", "category", "doc", "attributes"}, {"inherits"});
        prim.name = getString(document, "name");
        // The file name is how people find a prim's schema, the name is how code finds it.
        if (prim.name != file.stem().string()) fail("name \"" + prim.name + "\" differs from the file name");
        if (!isIdentifier(prim.name)) fail("name \"" + prim.name + "\" must be letters and digits");
        prim.usdType = getString(document, "usdType");
        prim.category = getString(document, "category");
        if (!kCategories.contains(prim.category)) fail("category must be rprim, sprim or bprim, got \"" + prim.category + "\"");
        prim.doc = getString(document, "doc");
        if (!document.at("attributes").is_array()) fail("\"attributes\" must be an array");
    } catch (const SchemaError& error) {
        errors.push_back(where + ": " + error.what());
        return std::nullopt;
    }

    // "inherits" names a file of attributes beside this one that several prim types share (as
    // USD's schemas inherit UsdGeomGprim): they come first, then the prim's own.
    json attributes = json::array();
    if (document.contains("inherits")) {
        const json& base = document.at("inherits");
        const fs::path baseFile = file.parent_path() / ((base.is_string() ? base.get<std::string>() : "") + ".json");
        std::ifstream baseStream(baseFile);
        json baseDocument;
        try {
            if (!base.is_string() || !baseStream) throw SchemaError("inherits: cannot open " + baseFile.string());
            baseDocument = json::parse(baseStream);
            checkKeys(baseDocument, {"doc", "attributes"}, {});
            if (!baseDocument.at("attributes").is_array()) throw SchemaError("inherits: \"attributes\" must be an array");
        } catch (const std::exception& error) {
            errors.push_back(where + ": " + error.what());
            return std::nullopt;
        }
        attributes = baseDocument.at("attributes");
    }
    // An attribute of the prim's own under an inherited name replaces it (USD's fallback override:
    // UsdGeomPlane is double-sided).
    for (const json& own : document.at("attributes")) {
        auto same = std::find_if(attributes.begin(), attributes.end(), [&](const json& inherited) {
            return own.is_object() && own.contains("name") && inherited.at("name") == own.at("name");
        });
        if (same != attributes.end()) *same = own;
        else attributes.push_back(own);
    }
    std::set<std::string> names;
    for (size_t i = 0; i < attributes.size(); ++i) {
        const json& object = attributes[i];
        // Name the attribute in messages even when the rest of it is broken.
        const std::string label = object.is_object() && object.contains("name") && object.at("name").is_string()
                                      ? object.at("name").get<std::string>()
                                      : "attribute #" + std::to_string(i);
        try {
            Attribute attribute = parseAttribute(object);
            if (!names.insert(attribute.name).second) fail("defined twice");
            prim.attributes.push_back(std::move(attribute));
        } catch (const SchemaError& error) {
            errors.push_back(where + ": " + label + ": " + error.what());
        }
    }
    if (errors.size() != errorsBefore) return std::nullopt;
    return prim;
}

// ------------------------------------------------------------------------------------------
// Output
// ------------------------------------------------------------------------------------------

// Shortest text that reads back as the same double, without an exponent: "0.18", "1000000".
std::string formatNumber(double value) {
    std::array<char, 400> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed);
    return std::string(buffer.data(), result.ptr);
}

std::string cppDouble(double value) {
    std::string text = formatNumber(value);
    if (text.find('.') == std::string::npos) text += ".0";
    return text;
}

std::string cppString(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            std::array<char, 8> escaped{};
            std::snprintf(escaped.data(), escaped.size(), "\\%03o", static_cast<unsigned>(static_cast<unsigned char>(c)));
            out += escaped.data();
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// "distantLight" -> "DistantLight", for C++ identifiers of generated arrays.
std::string capitalized(std::string name) {
    name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
    return name;
}

std::string tablesSource(const std::vector<Prim>& prims) {
    std::ostringstream out;
    out << "// Generated by schemas/generate_schema_tables.cpp from schemas/*.json: edit those, not this file.\n"
        << "#include \"schemas/schema.h\"\n\n"
        << "namespace obscura::schema {\nnamespace {\n";
    for (const Prim& prim : prims) {
        const std::string prefix = "k" + capitalized(prim.name);
        out << "\n// " << prim.name << "\n";
        // Token lists are named by attribute index: attribute names hold ':' and need not map
        // to distinct identifiers.
        for (size_t i = 0; i < prim.attributes.size(); ++i) {
            const Attribute& attribute = prim.attributes[i];
            if (attribute.tokens.empty()) continue;
            out << "constexpr const char* " << prefix << "Tokens" << i << "[] = {  // " << attribute.name << "\n   ";
            for (const std::string& token : attribute.tokens) out << " " << cppString(token) << ",";
            out << "\n};\n";
        }
        out << "constexpr AttributeSchema " << prefix << "Attributes[] = {\n";
        for (size_t i = 0; i < prim.attributes.size(); ++i) {
            const Attribute& a = prim.attributes[i];
            const bool isString = a.type->kind == Kind::Token || a.type->kind == Kind::Path;
            const size_t defaultCount = !a.hasDefault ? 0 : isString ? 1 : a.defaultNumbers.size();
            out << "    {.name = " << cppString(a.name) << ",\n"
                << "     .type = AttrType::" << a.type->enumerator << ",\n"
                << "     .usdType = " << cppString(a.usdType) << ",\n"
                << "     .defaultCount = " << defaultCount << ",\n"
                << "     .defaultNumbers = {";
            for (size_t n = 0; n < a.defaultNumbers.size(); ++n) out << (n ? ", " : "") << cppDouble(a.defaultNumbers[n]);
            out << "},\n"
                << "     .defaultToken = " << (a.hasDefault && isString ? cppString(a.defaultString) : "nullptr") << ",\n"
                << "     .units = " << cppString(a.units) << ",\n"
                << "     .timeSampled = " << (a.timeSampled ? "true" : "false") << ",\n"
                << "     .dirtyBit = " << kDirtyBits.at(a.dirtyBit) << ",\n"
                << "     .interpolation = " << (a.interpolation ? cppString(*a.interpolation) : "nullptr") << ",\n"
                << "     .tokens = " << (a.tokens.empty() ? "nullptr" : prefix + "Tokens" + std::to_string(i)) << ",\n"
                << "     .tokenCount = " << a.tokens.size() << ",\n"
                << "     .doc = " << cppString(a.doc) << "},\n";
        }
        out << "};\n";
    }
    out << "\nconstexpr PrimSchema kPrimSchemas[] = {\n";
    for (const Prim& prim : prims) {
        out << "    {.name = " << cppString(prim.name) << ",\n"
            << "     .usdType = " << cppString(prim.usdType) << ",\n"
            << "     .category = " << cppString(prim.category) << ",\n"
            << "     .attributes = k" << capitalized(prim.name) << "Attributes,\n"
            << "     .attributeCount = " << prim.attributes.size() << ",\n"
            << "     .doc = " << cppString(prim.doc) << "},\n";
    }
    out << "};\n\n}  // namespace\n\n"
        << "std::span<const PrimSchema> primSchemas() { return kPrimSchemas; }\n\n"
        << "}  // namespace obscura::schema\n";
    return out.str();
}

// Table cells cannot contain '|' or line breaks.
std::string markdownCell(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '|') out += "\\|";
        else out += c == '\n' ? ' ' : c;
    }
    return out;
}

std::string lowerCase(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// The schema type, and USD's declaration where it says more ("point3f[]", "uniform token").
std::string markdownType(const Attribute& a) {
    const std::string type = "`" + std::string(a.type->name) + "`";
    return a.usdType == a.type->name ? type : type + " (USD `" + markdownCell(a.usdType) + "`)";
}

std::string markdownDefault(const Attribute& a) {
    if (!a.hasDefault) return "—";
    switch (a.type->kind) {
    case Kind::Bool:
        return a.defaultNumbers[0] != 0.0 ? "`true`" : "`false`";
    case Kind::Token:
    case Kind::Path:
        return "`" + a.defaultString + "`";
    case Kind::Number:
    case Kind::Array:
        break;
    }
    if (a.defaultNumbers.size() == 16) {
        bool identity = true;
        for (size_t i = 0; i < 16; ++i) identity = identity && a.defaultNumbers[i] == (i % 5 == 0 ? 1.0 : 0.0);
        if (identity) return "identity";
    }
    std::string text;
    for (size_t i = 0; i < a.defaultNumbers.size(); ++i) text += (i ? ", " : "") + formatNumber(a.defaultNumbers[i]);
    return a.defaultNumbers.size() == 1 ? "`" + text + "`" : "`(" + text + ")`";
}

std::string markdownDescription(const Attribute& a) {
    std::string text = a.doc;
    if (!a.tokens.empty()) {
        text += " Values:";
        for (size_t i = 0; i < a.tokens.size(); ++i) text += (i ? ", `" : " `") + a.tokens[i] + "`";
        text += ".";
    }
    if (a.interpolation) text += " Default interpolation: `" + *a.interpolation + "`.";
    return markdownCell(text);
}

std::string referenceMarkdown(const std::vector<Prim>& prims) {
    std::ostringstream out;
    out << "# Prim schemas\n\n"
        << "<!-- Generated by schemas/generate_schema_tables.cpp from schemas/*.json; the test\n"
        << "     schemas_doc_up_to_date fails when this copy differs from the generated one. -->\n\n"
        << "What the delegate reads from the host for each prim type. The delegate pulls an attribute\n"
        << "through the scene delegate's `getValue` when one of the prim's dirty bits listed for it is set\n"
        << "(`transform` goes through `sampleTransform` instead); when the host answers\n"
        << "`OBSCURA_ERROR_NOT_FOUND` the default below is used, and \"—\" means there is none (the\n"
        << "attribute is absent). *Time-sampled* says whether USD allows the attribute to vary over time;\n"
        << "values of the wrong type, non-finite numbers and tokens outside the listed values are bad\n"
        << "prim data.\n\n";
    // Markdown renderers derive heading anchors in lower case.
    for (const Prim& prim : prims) out << "- [" << prim.name << "](#" << lowerCase(prim.name) << ")\n";
    for (const Prim& prim : prims) {
        out << "\n## " << prim.name << "\n\n"
            << "USD type `" << prim.usdType << "`, " << prim.category << ". " << prim.doc << "\n\n"
            << "| Attribute | Type | Default | Units | Time-sampled | Dirty bit | Description |\n"
            << "|---|---|---|---|---|---|---|\n";
        for (const Attribute& a : prim.attributes) {
            out << "| `" << markdownCell(a.name) << "` | " << markdownType(a) << " | " << markdownDefault(a) << " | " << (a.units.empty() ? "—" : markdownCell(a.units)) << " | "
                << (a.timeSampled ? "yes" : "no") << " | `" << kDirtyBits.at(a.dirtyBit) << "` | "
                << markdownDescription(a) << " |\n";
        }
    }
    return out.str();
}

bool writeFile(const fs::path& path, const std::string& text) {
    std::error_code error;
    if (path.has_parent_path()) fs::create_directories(path.parent_path(), error);
    std::ofstream stream(path, std::ios::binary);
    stream << text;
    stream.close();
    if (!stream) std::cerr << "generate_schema_tables: cannot write " << path.string() << "\n";
    return static_cast<bool>(stream);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: generate_schema_tables <tables.cpp> <schemas.md> <schema.json>...\n";
        return 2;
    }
    std::vector<std::string> errors;
    std::vector<Prim> prims;
    std::set<std::string> primNames;
    for (int i = 3; i < argc; ++i) {
        std::optional<Prim> prim = readPrim(argv[i], errors);
        if (!prim) continue;
        if (!primNames.insert(prim->name).second) {
            errors.push_back(fs::path(argv[i]).filename().string() + ": prim \"" + prim->name + "\" is defined twice");
            continue;
        }
        prims.push_back(std::move(*prim));
    }
    if (!errors.empty()) {
        for (const std::string& error : errors) std::cerr << "error: " << error << "\n";
        return 1;
    }
    return writeFile(argv[1], tablesSource(prims)) && writeFile(argv[2], referenceMarkdown(prims)) ? 0 : 1;
}
