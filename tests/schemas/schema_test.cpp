// Tests of the prim schema tables (schemas/*.json through the generator), of checkValue, and of
// the generator's rejection of malformed schemas.
#include "schemas/schema.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace obscura::schema {
namespace {

const AttributeSchema& attr(const char* prim, const char* name) {
    const PrimSchema* schema = findPrimSchema(prim);
    if (!schema) throw std::runtime_error(std::string("no prim schema ") + prim);
    const AttributeSchema* attribute = findAttribute(*schema, name);
    if (!attribute) throw std::runtime_error(std::string("no attribute ") + prim + "." + name);
    return *attribute;
}

// --- Tables ------------------------------------------------------------------------------------

TEST(SchemaTables, EveryPrimTypeIsFound) {
    const std::pair<const char*, const char*> expected[] = {
        {"mesh", "rprim"},     {"camera", "sprim"},   {"distantLight", "sprim"},
        {"sphereLight", "sprim"}, {"material", "sprim"}, {"renderBuffer", "bprim"},
        {"instancer", "rprim"},   {"domeLight", "sprim"},  {"rectLight", "sprim"},
        {"diskLight", "sprim"},   {"cylinderLight", "sprim"}, {"cube", "rprim"},       {"sphere", "rprim"},
        {"cylinder", "rprim"},    {"cylinder1", "rprim"},  {"cone", "rprim"},
        {"capsule", "rprim"},     {"capsule1", "rprim"},   {"plane", "rprim"},
        {"basisCurves", "rprim"}, {"points", "rprim"},     {"nurbsPatch", "rprim"}};
    EXPECT_EQ(primSchemas().size(), std::size(expected));
    for (const auto& [name, category] : expected) {
        const PrimSchema* prim = findPrimSchema(name);
        ASSERT_NE(prim, nullptr) << name;
        EXPECT_STREQ(prim->category, category) << name;
        EXPECT_GT(prim->attributeCount, 0u) << name;
    }
}

// plugInfo.json's primTypes are made from the schema files: every prim type, under its category,
// and nothing else.
TEST(SchemaTables, PlugInfoDeclaresEveryPrimType) {
    std::ifstream file(OBSCURA_PLUGIN_INFO);
    ASSERT_TRUE(file) << OBSCURA_PLUGIN_INFO;
    nlohmann::json info = nlohmann::json::parse(file);
    const nlohmann::json& types = info["Plugins"][0]["Info"]["Types"]["ObscuraRendererPlugin"]["primTypes"];
    size_t declared = 0;
    for (const char* category : {"rprim", "sprim", "bprim"}) declared += types[std::string(category) + "s"].size();
    EXPECT_EQ(declared, primSchemas().size());
    for (const PrimSchema& prim : primSchemas()) {
        const nlohmann::json& list = types[std::string(prim.category) + "s"];
        EXPECT_NE(std::find(list.begin(), list.end(), prim.name), list.end()) << prim.name << " in " << prim.category << "s";
    }
}

TEST(SchemaTables, UnknownNamesGiveNull) {
    EXPECT_EQ(findPrimSchema("volume"), nullptr);
    EXPECT_EQ(findPrimSchema("gprim"), nullptr);  // the attributes gprims share, not a prim type
    EXPECT_EQ(findPrimSchema("Mesh"), nullptr);   // prim type tokens, not USD type names
    EXPECT_EQ(findPrimSchema(""), nullptr);
    const PrimSchema& mesh = *findPrimSchema("mesh");
    EXPECT_EQ(findAttribute(mesh, "inputs:roughness"), nullptr);
    EXPECT_EQ(findAttribute(mesh, "Points"), nullptr);
    EXPECT_EQ(findAttribute(mesh, ""), nullptr);
}

TEST(SchemaTables, DefaultsMatchUsdFallbacks) {
    const AttributeSchema& aperture = attr("camera", "horizontalAperture");
    ASSERT_EQ(aperture.defaultCount, 1u);
    EXPECT_DOUBLE_EQ(aperture.defaultNumbers[0], 20.955);
    EXPECT_DOUBLE_EQ(attr("camera", "verticalAperture").defaultNumbers[0], 15.2908);
    EXPECT_DOUBLE_EQ(attr("camera", "focalLength").defaultNumbers[0], 50.0);
    const AttributeSchema& clipping = attr("camera", "clippingRange");
    ASSERT_EQ(clipping.defaultCount, 2u);
    EXPECT_DOUBLE_EQ(clipping.defaultNumbers[0], 1.0);
    EXPECT_DOUBLE_EQ(clipping.defaultNumbers[1], 1000000.0);

    EXPECT_DOUBLE_EQ(attr("distantLight", "inputs:intensity").defaultNumbers[0], 50000.0);
    EXPECT_DOUBLE_EQ(attr("distantLight", "inputs:angle").defaultNumbers[0], 0.53);
    EXPECT_DOUBLE_EQ(attr("distantLight", "inputs:shadow:enable").defaultNumbers[0], 1.0);
    EXPECT_DOUBLE_EQ(attr("sphereLight", "inputs:intensity").defaultNumbers[0], 1.0);
    EXPECT_DOUBLE_EQ(attr("sphereLight", "inputs:radius").defaultNumbers[0], 0.5);
    EXPECT_DOUBLE_EQ(attr("sphereLight", "inputs:colorTemperature").defaultNumbers[0], 6500.0);

    const AttributeSchema& diffuse = attr("material", "inputs:diffuseColor");
    ASSERT_EQ(diffuse.defaultCount, 3u);
    for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(diffuse.defaultNumbers[i], 0.18);
    EXPECT_DOUBLE_EQ(attr("material", "inputs:roughness").defaultNumbers[0], 0.5);
    EXPECT_DOUBLE_EQ(attr("material", "inputs:clearcoatRoughness").defaultNumbers[0], 0.01);
    EXPECT_DOUBLE_EQ(attr("material", "inputs:ior").defaultNumbers[0], 1.5);

    EXPECT_STREQ(attr("mesh", "orientation").defaultToken, "rightHanded");
    EXPECT_STREQ(attr("mesh", "subdivisionScheme").defaultToken, "catmullClark");
    EXPECT_STREQ(attr("mesh", "visibility").defaultToken, "inherited");
    EXPECT_DOUBLE_EQ(attr("mesh", "doubleSided").defaultNumbers[0], 0.0);
    EXPECT_DOUBLE_EQ(attr("mesh", "obscura:refineLevel").defaultNumbers[0], -1.0);
    EXPECT_STREQ(attr("mesh", "subsetFamily:materialBind:familyType").defaultToken, "unrestricted");
    EXPECT_STREQ(attr("renderBuffer", "format").defaultToken, "float32Vec4");
}

TEST(SchemaTables, MeshDetails) {
    const AttributeSchema& transform = attr("mesh", "transform");
    ASSERT_EQ(transform.type, AttrType::Matrix4d);
    ASSERT_EQ(transform.defaultCount, 16u);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(transform.defaultNumbers[i], i % 5 == 0 ? 1.0 : 0.0) << i;

    const AttributeSchema& color = attr("mesh", "primvars:displayColor");
    EXPECT_EQ(color.type, AttrType::Float3Array);
    EXPECT_EQ(color.defaultCount, 0u);  // no colour of its own unless authored
    EXPECT_STREQ(color.interpolation, "constant");
    EXPECT_STREQ(attr("mesh", "normals").interpolation, "vertex");
    EXPECT_EQ(attr("mesh", "points").interpolation, nullptr);

    const AttributeSchema& orientation = attr("mesh", "orientation");
    ASSERT_EQ(orientation.tokenCount, 2u);
    EXPECT_STREQ(orientation.tokens[1], "leftHanded");
    EXPECT_FALSE(orientation.timeSampled);
    EXPECT_TRUE(attr("mesh", "points").timeSampled);
    EXPECT_EQ(attr("mesh", "material:binding").defaultToken, nullptr);
}

TEST(SchemaTables, DirtyBitsMatchTheHeader) {
    EXPECT_EQ(attr("mesh", "transform").dirtyBit, OBSCURA_DIRTY_TRANSFORM);
    EXPECT_EQ(attr("mesh", "points").dirtyBit, OBSCURA_DIRTY_POINTS);
    EXPECT_EQ(attr("mesh", "faceVertexIndices").dirtyBit, OBSCURA_DIRTY_TOPOLOGY);
    EXPECT_EQ(attr("mesh", "orientation").dirtyBit, OBSCURA_DIRTY_TOPOLOGY);
    EXPECT_EQ(attr("mesh", "normals").dirtyBit, OBSCURA_DIRTY_NORMALS);
    EXPECT_EQ(attr("mesh", "primvars:displayOpacity").dirtyBit, OBSCURA_DIRTY_PRIMVAR);
    EXPECT_EQ(attr("mesh", "material:binding").dirtyBit, OBSCURA_DIRTY_MATERIAL_ID);
    EXPECT_EQ(attr("mesh", "visibility").dirtyBit, OBSCURA_DIRTY_VISIBILITY);
    EXPECT_EQ(attr("mesh", "doubleSided").dirtyBit, OBSCURA_DIRTY_DOUBLE_SIDED);
    EXPECT_EQ(attr("camera", "fStop").dirtyBit, OBSCURA_DIRTY_PARAMS);
    EXPECT_EQ(attr("renderBuffer", "dimensions").dirtyBit, OBSCURA_DIRTY_PARAMS);
}

TEST(SchemaTables, EveryAttributeIsComplete) {
    for (const PrimSchema& prim : primSchemas()) {
        EXPECT_STRNE(prim.doc, "") << prim.name;
        for (const AttributeSchema& a : std::span(prim.attributes, prim.attributeCount)) {
            EXPECT_STRNE(a.doc, "") << prim.name << "." << a.name;
            EXPECT_NE(a.units, nullptr) << prim.name << "." << a.name;
            EXPECT_EQ(std::popcount(a.dirtyBit), 1) << prim.name << "." << a.name;
            EXPECT_EQ(findAttribute(prim, a.name), &a) << prim.name << "." << a.name;
        }
    }
}

// --- checkValue --------------------------------------------------------------------------------

ObscuraValue scalar(ObscuraValueType type, const void* data) { return {type, 0, 1, data}; }
ObscuraValue array(ObscuraValueType type, size_t count, const void* data) { return {type, 1, count, data}; }

TEST(CheckValue, AcceptsMatchingTypes) {
    const float roughness = 0.25f;
    const double roughnessD = 0.25;
    EXPECT_EQ(checkValue(attr("material", "inputs:roughness"), scalar(OBSCURA_VALUE_FLOAT, &roughness)), "");
    EXPECT_EQ(checkValue(attr("material", "inputs:roughness"), scalar(OBSCURA_VALUE_DOUBLE, &roughnessD)), "");
    EXPECT_EQ(checkValue(attr("camera", "shutter:open"), scalar(OBSCURA_VALUE_DOUBLE, &roughnessD)), "");

    const float points[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    EXPECT_EQ(checkValue(attr("mesh", "points"), array(OBSCURA_VALUE_FLOAT3, 3, points)), "");
    EXPECT_EQ(checkValue(attr("mesh", "points"), array(OBSCURA_VALUE_FLOAT3, 0, nullptr)), "");
    const int32_t indices[] = {0, 1, 2};
    EXPECT_EQ(checkValue(attr("mesh", "faceVertexIndices"), array(OBSCURA_VALUE_INT, 3, indices)), "");

    const int32_t one = 1;
    EXPECT_EQ(checkValue(attr("mesh", "doubleSided"), scalar(OBSCURA_VALUE_BOOL, &one)), "");
    EXPECT_EQ(checkValue(attr("mesh", "doubleSided"), scalar(OBSCURA_VALUE_INT, &one)), "");

    const char* leftHanded = "leftHanded";
    EXPECT_EQ(checkValue(attr("mesh", "orientation"), scalar(OBSCURA_VALUE_TOKEN, &leftHanded)), "");
    const char* material = "/World/Looks/Red";
    EXPECT_EQ(checkValue(attr("mesh", "material:binding"), scalar(OBSCURA_VALUE_PATH, &material)), "");

    const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    EXPECT_EQ(checkValue(attr("camera", "transform"), scalar(OBSCURA_VALUE_MATRIX4D, identity)), "");
    const int32_t size[] = {640, 480};
    EXPECT_EQ(checkValue(attr("renderBuffer", "dimensions"), scalar(OBSCURA_VALUE_INT2, size)), "");
    const float clipping[] = {0.1f, 100.0f};
    EXPECT_EQ(checkValue(attr("camera", "clippingRange"), scalar(OBSCURA_VALUE_FLOAT2, clipping)), "");
}

TEST(CheckValue, RejectsWrongTypeOrShape) {
    const char* token = "rough";
    EXPECT_EQ(checkValue(attr("material", "inputs:roughness"), scalar(OBSCURA_VALUE_TOKEN, &token)),
              "inputs:roughness: expected float, got token");

    const float point[] = {0, 0, 0};
    EXPECT_EQ(checkValue(attr("mesh", "points"), scalar(OBSCURA_VALUE_FLOAT3, point)),
              "points: expected float3[], got float3");
    EXPECT_EQ(checkValue(attr("material", "inputs:diffuseColor"), array(OBSCURA_VALUE_FLOAT3, 1, point)),
              "inputs:diffuseColor: expected float3, got float3[]");
    EXPECT_EQ(checkValue(attr("material", "inputs:diffuseColor"), {OBSCURA_VALUE_FLOAT3, 0, 2, point}),
              "inputs:diffuseColor: expected one value, got 2");

    const double indices[] = {0, 1, 2};
    EXPECT_EQ(checkValue(attr("mesh", "faceVertexIndices"), array(OBSCURA_VALUE_DOUBLE, 3, indices)),
              "faceVertexIndices: expected int[], got double[]");
    const char* material = "/Looks/M";
    EXPECT_EQ(checkValue(attr("mesh", "material:binding"), scalar(OBSCURA_VALUE_TOKEN, &material)),
              "material:binding: expected path, got token");
    EXPECT_EQ(checkValue(attr("mesh", "transform"), scalar(static_cast<ObscuraValueType>(15), point)),
              "transform: expected matrix4d, got unknown value type 15");
    EXPECT_EQ(checkValue(attr("mesh", "points"), array(OBSCURA_VALUE_FLOAT3, 3, nullptr)), "points: data is null");
}

TEST(CheckValue, RejectsNaNAndInf) {
    std::vector<float> points(3 * 20, 1.0f);
    points[12 * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(checkValue(attr("mesh", "points"), array(OBSCURA_VALUE_FLOAT3, 20, points.data())),
              "points: element 12 is NaN");
    points[12 * 3 + 1] = 1.0f;
    points[19 * 3 + 2] = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(checkValue(attr("mesh", "points"), array(OBSCURA_VALUE_FLOAT3, 20, points.data())),
              "points: element 19 is Inf");

    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(checkValue(attr("material", "inputs:opacity"), scalar(OBSCURA_VALUE_FLOAT, &nan)),
              "inputs:opacity: value is NaN");
    const double infinity = std::numeric_limits<double>::infinity();
    EXPECT_EQ(checkValue(attr("camera", "shutter:close"), scalar(OBSCURA_VALUE_DOUBLE, &infinity)),
              "shutter:close: value is Inf");
    double matrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    matrix[13] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(checkValue(attr("mesh", "transform"), scalar(OBSCURA_VALUE_MATRIX4D, matrix)),
              "transform: value is NaN");
}

TEST(CheckValue, RejectsBadTokensPathsAndBools) {
    const char* sideways = "sideways";
    EXPECT_EQ(checkValue(attr("mesh", "orientation"), scalar(OBSCURA_VALUE_TOKEN, &sideways)),
              "orientation: \"sideways\" is not one of rightHanded, leftHanded");
    const char* upperCase = "Perspective";
    EXPECT_NE(checkValue(attr("camera", "projection"), scalar(OBSCURA_VALUE_TOKEN, &upperCase)), "");
    const char* null = nullptr;
    EXPECT_EQ(checkValue(attr("renderBuffer", "format"), scalar(OBSCURA_VALUE_TOKEN, &null)),
              "format: value is a null string");
    const char* relative = "Looks/M";
    EXPECT_EQ(checkValue(attr("mesh", "material:binding"), scalar(OBSCURA_VALUE_PATH, &relative)),
              "material:binding: path \"Looks/M\" is not absolute");
    const int32_t two = 2;
    EXPECT_EQ(checkValue(attr("mesh", "doubleSided"), scalar(OBSCURA_VALUE_BOOL, &two)),
              "doubleSided: bool value is 2, not 0 or 1");
}

// --- The generator -----------------------------------------------------------------------------

struct GeneratorRun {
    int exitCode = -1;
    std::string log;
    bool wroteOutput = false;
};

// Runs the generator on one schema file `<name>.json` holding `text`, in a fresh directory.
GeneratorRun runGenerator(const std::string& name, const std::string& text) {
    // Parametrised test names contain '/'; ctest may run tests in parallel, hence the pid.
    std::string testName = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(testName.begin(), testName.end(), '/', '_');
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("obscura_schema_test_" + std::to_string(getpid()) + "_" + testName);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::filesystem::path schema = dir / (name + ".json");
    std::ofstream(schema) << text;

    const std::filesystem::path tables = dir / "tables.cpp";
    const std::filesystem::path doc = dir / "schemas.md";
    const std::filesystem::path log = dir / "log.txt";
    const std::string command = "\"" OBSCURA_SCHEMA_GENERATOR "\" \"" + tables.string() + "\" \"" + doc.string() +
                                "\" \"" + schema.string() + "\" > \"" + log.string() + "\" 2>&1";
    const int status = std::system(command.c_str());

    GeneratorRun run;
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ostringstream logText;
    logText << std::ifstream(log).rdbuf();
    run.log = logText.str();
    run.wroteOutput = std::filesystem::exists(tables) || std::filesystem::exists(doc);
    std::filesystem::remove_all(dir);
    return run;
}

// A one-attribute schema whose attribute is `attribute` (JSON object members, without braces).
std::string schemaWith(const std::string& attribute) {
    return R"({"name": "widget", "usdType": "Widget", "category": "sprim", "doc": "A test prim.",
               "attributes": [ {)" + attribute + "} ] }";
}

const std::string kGoodAttribute = R"("name": "size", "usdType": "float3", "type": "float3",
    "default": [1, 2, 3], "units": "scene units", "timeSampled": true, "dirtyBit": "params",
    "doc": "Size of the widget.")";

TEST(Generator, AcceptsAValidSchema) {
    const GeneratorRun run = runGenerator("widget", schemaWith(kGoodAttribute));
    EXPECT_EQ(run.exitCode, 0) << run.log;
    EXPECT_TRUE(run.wroteOutput);
}

struct BadSchema {
    const char* label;
    std::string text;
    const char* expectedMessage;  // must appear in the generator's output
};

// Names the case in test listings instead of gtest's byte dump.
void PrintTo(const BadSchema& schema, std::ostream* out) { *out << schema.label; }

class GeneratorRejects : public ::testing::TestWithParam<BadSchema> {};

TEST_P(GeneratorRejects, NamingFileAndAttribute) {
    const GeneratorRun run = runGenerator("widget", GetParam().text);
    EXPECT_EQ(run.exitCode, 1) << run.log;
    EXPECT_NE(run.log.find(GetParam().expectedMessage), std::string::npos) << run.log;
    EXPECT_FALSE(run.wroteOutput);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, GeneratorRejects,
    ::testing::Values(
        BadSchema{"UnknownType", schemaWith(replaced(kGoodAttribute, R"("type": "float3")", R"("type": "vec3")")),
                  "widget.json: size: unknown type \"vec3\""},
        BadSchema{"DefaultOfWrongShape", schemaWith(replaced(kGoodAttribute, "[1, 2, 3]", "[1, 2]")),
                  "widget.json: size: default of a float3 must be an array of 3 numbers, got [1,2]"},
        BadSchema{"DefaultOfWrongType", schemaWith(replaced(kGoodAttribute, "[1, 2, 3]", R"("big")")),
                  "widget.json: size: default of a float3 must be an array of 3 numbers"},
        BadSchema{"UnknownDirtyBit", schemaWith(replaced(kGoodAttribute, R"("params")", R"("sizes")")),
                  "widget.json: size: unknown dirty bit \"sizes\""},
        BadSchema{"MisspeltKey", schemaWith(replaced(kGoodAttribute, "timeSampled", "timesampled")),
                  "widget.json: size: missing key \"timeSampled\""},
        BadSchema{"TokenDefaultNotAllowed",
                  schemaWith(R"("name": "mode", "usdType": "token", "type": "token", "default": "c",
                                "tokens": ["a", "b"], "units": null, "timeSampled": false,
                                "dirtyBit": "params", "doc": "A mode.")"),
                  "widget.json: mode: default \"c\" is not one of the allowed tokens"},
        BadSchema{"NameDiffersFromFile", replaced(schemaWith(kGoodAttribute), R"("widget")", R"("gadget")"),
                  "widget.json: name \"gadget\" differs from the file name"},
        BadSchema{"NotJson", "{ \"name\": ", "widget.json: [json.exception.parse_error"}),
    [](const ::testing::TestParamInfo<BadSchema>& param) { return std::string(param.param.label); });

}  // namespace
}  // namespace obscura::schema
