// glTF, OBJ and FBX files (tests/import/data) converted to USD text, composed by the harness's
// stage and checked against the values in the source files.
#include "harness/image/png_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <variant>
#include <vector>

#include "harness/import/assimp_to_usda.h"
#include "harness/usda/skinning.h"
#include "harness/usda/stage.h"

namespace obscura::harness {
namespace {

using usda::Prim;
using usda::Stage;
using Vec3 = std::array<double, 3>;

const std::filesystem::path kData = OBSCURA_IMPORT_TEST_DATA;

ImportResult importOk(const std::filesystem::path& file) {
    auto result = importWithAssimp(file);
    if (const ImportError* error = std::get_if<ImportError>(&result)) {
        ADD_FAILURE() << "import failed: " << error->message;
        return {};
    }
    return std::get<ImportResult>(std::move(result));
}

// The imported file composed as the harness will: the text under the imported file's path.
struct Imported {
    ImportResult result;
    std::unique_ptr<Stage> stage;

    explicit Imported(const std::string& name) : result(importOk(kData / name)) {
        auto composed = Stage::openFromString(result.usda, (kData / name).string());
        if (const usda::Error* error = std::get_if<usda::Error>(&composed)) {
            ADD_FAILURE() << "the USD text does not parse: " << error->str() << "\n" << result.usda;
            return;
        }
        stage = std::get<std::unique_ptr<Stage>>(std::move(composed));
    }

    const Prim& prim(const std::string& path, const std::string& type) const {
        static const Prim missing;
        const Prim* found = stage ? stage->find(path) : nullptr;
        if (!found) {
            ADD_FAILURE() << "no prim " << path;
            return missing;
        }
        EXPECT_EQ(found->typeName, type) << path;
        return *found;
    }

    std::vector<double> numbers(const std::string& path, const std::string& attribute, double time = 0) const {
        const Prim* found = stage ? stage->find(path) : nullptr;
        const usda::Attribute* attr = found ? found->attribute(attribute) : nullptr;
        const std::optional<usda::Value> value = attr ? attr->evaluate(time) : std::nullopt;
        if (!value) {
            ADD_FAILURE() << "no value for " << path << "." << attribute;
            return {};
        }
        return value->numbers;
    }

    std::string token(const std::string& path, const std::string& attribute) const {
        const Prim* found = stage ? stage->find(path) : nullptr;
        const usda::Attribute* attr = found ? found->attribute(attribute) : nullptr;
        if (!attr || !attr->defaultValue || attr->defaultValue->strings.empty()) {
            ADD_FAILURE() << "no string value for " << path << "." << attribute;
            return {};
        }
        return attr->defaultValue->strings.front();
    }

    std::string connection(const std::string& path, const std::string& attribute) const {
        const Prim* found = stage ? stage->find(path) : nullptr;
        const usda::Attribute* attr = found ? found->attribute(attribute) : nullptr;
        return attr && attr->connection ? *attr->connection : std::string();
    }

    // Where a local point of the prim lies in the world (USD: row vectors).
    Vec3 worldPoint(const std::string& path, const Vec3& local, double time = 0) const {
        const Prim* found = stage ? stage->find(path) : nullptr;
        if (!found) {
            ADD_FAILURE() << "no prim " << path;
            return {};
        }
        const std::array<double, 16> m = stage->worldTransform(*found, time);
        Vec3 out{};
        for (size_t c = 0; c < 3; ++c) out[c] = local[0] * m[c] + local[1] * m[4 + c] + local[2] * m[8 + c] + m[12 + c];
        return out;
    }

    Vec3 worldDirection(const std::string& path, const Vec3& local) const {
        const Vec3 origin = worldPoint(path, {0, 0, 0});
        const Vec3 tip = worldPoint(path, local);
        return {tip[0] - origin[0], tip[1] - origin[1], tip[2] - origin[2]};
    }

    bool warned(const std::string& fragment) const {
        for (const std::string& warning : result.warnings)
            if (warning.find(fragment) != std::string::npos) return true;
        return false;
    }
};

void expectNear(const std::vector<double>& actual, const std::vector<double>& expected, double tolerance = 1e-5) {
    ASSERT_EQ(actual.size(), expected.size());
    for (size_t i = 0; i < actual.size(); ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "element " << i;
}

void expectNear(const Vec3& actual, const Vec3& expected, double tolerance = 1e-5) {
    expectNear(std::vector<double>(actual.begin(), actual.end()), std::vector<double>(expected.begin(), expected.end()),
               tolerance);
}

std::vector<double> flatten(const std::vector<Vec3>& vectors) {
    std::vector<double> out;
    for (const Vec3& v : vectors) out.insert(out.end(), v.begin(), v.end());
    return out;
}

// ---- glTF -------------------------------------------------------------------------------------

const std::string kQuad = "/Root/Root_Group/Parent/Child/Quad_0";
const std::string kLooks = "/Root/Looks";

TEST(GltfImport, LayerMetadataAndPrimTypes) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const usda::StageMetadata& meta = gltf.stage->metadata();
    EXPECT_EQ(meta.upAxis, "Y");
    EXPECT_EQ(meta.defaultPrim, "Root");
    EXPECT_EQ(meta.metersPerUnit, 1.0);
    // Assimp's glTF animation clock is in milliseconds; the key times are the time codes.
    EXPECT_EQ(meta.timeCodesPerSecond, 1000.0);
    EXPECT_EQ(meta.startTimeCode, 0.0);
    EXPECT_EQ(meta.endTimeCode, 1000.0);

    gltf.prim("/Root", "Xform");
    gltf.prim(kLooks, "Scope");
    gltf.prim("/Root/Root_Group", "Xform");
    gltf.prim(kQuad, "Mesh");
    gltf.prim("/Root/Main_Camera/Main_Camera", "Camera");
    gltf.prim("/Root/Sun/Sun", "DistantLight");
    gltf.prim("/Root/Bulb/Bulb", "SphereLight");
    gltf.prim(kLooks + "/Painted_Metal", "Material");
    gltf.prim(kLooks + "/Painted_Metal/Surface", "Shader");
}

TEST(GltfImport, NamesAreIdentifiersUniqueAmongSiblings) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    // "Root Group", and two nodes both named "Dup".
    gltf.prim("/Root/Root_Group", "Xform");
    gltf.prim("/Root/Dup", "Xform");
    gltf.prim("/Root/Dup_1", "Xform");
}

TEST(GltfImport, MeshMatchesTheSource) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const Prim& quad = gltf.prim(kQuad, "Mesh");
    expectNear(gltf.numbers(kQuad, "faceVertexCounts"), {3, 3});
    expectNear(gltf.numbers(kQuad, "faceVertexIndices"), {0, 1, 2, 0, 2, 3});
    expectNear(gltf.numbers(kQuad, "points"), flatten({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}));
    expectNear(gltf.numbers(kQuad, "normals"), flatten({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}));
    expectNear(gltf.numbers(kQuad, "primvars:displayColor"), flatten({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}));
    for (const char* primvar : {"normals", "primvars:st", "primvars:displayColor"}) {
        const usda::Attribute* attr = quad.attribute(primvar);
        ASSERT_TRUE(attr && attr->metadata.count("interpolation")) << primvar;
        EXPECT_EQ(attr->metadata.at("interpolation").strings.front(), "vertex") << primvar;
    }
    EXPECT_EQ(gltf.token(kQuad, "subdivisionScheme"), "none");
    expectNear(gltf.numbers(kQuad, "doubleSided"), {1});
    const usda::Relationship* binding = quad.relationship("material:binding");
    ASSERT_TRUE(binding);
    EXPECT_EQ(binding->targets, std::vector<std::string>{kLooks + "/Painted_Metal"});
}

TEST(GltfImport, TextureCoordinatesHaveUsdsBottomLeftOrigin) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    // The file's TEXCOORD_0 (top-left origin) is (0,1) (1,1) (1,0) (0,0): st = (u, 1 - v).
    expectNear(gltf.numbers(kQuad, "primvars:st"), {0, 0, 1, 0, 1, 1, 0, 1});
}

TEST(GltfImport, PointPrimitivesAreDroppedWithAWarning) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    EXPECT_FALSE(gltf.stage->find("/Root/Root_Group/Parent/Child/Quad_1"));
    EXPECT_TRUE(gltf.warned("3 point and line primitives dropped"));
}

TEST(GltfImport, TransformsComposeToTheSourcesWorldPositions) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    // Child (0,0,2) in Parent (1,0,0) in Root Group (turned 90 degrees about +Y, then moved to z = -1).
    expectNear(gltf.worldPoint(kQuad, {0, 0, 0}), {2, 0, -2});
    expectNear(gltf.worldPoint(kQuad, {1, 0, 0}), {2, 0, -3});
    expectNear(gltf.worldPoint("/Root/Main_Camera/Main_Camera", {0, 0, 0}), {0, 1, 5});
}

TEST(GltfImport, AnimationInterpolatesTranslations) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string parent = "/Root/Root_Group/Parent";
    const usda::Attribute* order = gltf.prim(parent, "Xform").attribute("xformOpOrder");
    ASSERT_TRUE(order && order->defaultValue);
    EXPECT_EQ(order->defaultValue->strings,
              (std::vector<std::string>{"xformOp:translate", "xformOp:orient", "xformOp:scale"}));
    // Parent moves from x = 1 (t = 0 ms) to x = 3 (t = 1000 ms); Root Group turns +x into -z.
    expectNear(gltf.numbers(parent, "xformOp:translate", 250), {1.5, 0, 0});
    expectNear(gltf.worldPoint(kQuad, {0, 0, 0}, 500), {2, 0, -3});
    expectNear(gltf.worldPoint(kQuad, {0, 0, 0}, 1000), {2, 0, -4});
    const std::vector<double> times = gltf.stage->transformSampleTimes(*gltf.stage->find(kQuad));
    EXPECT_EQ(times, (std::vector<double>{0, 1000}));
}

// skinned.gltf: a two-joint arm whose elbow bends 90 degrees about +Z over the first second (t in ms).
TEST(GltfImport, SkinsArePosedThroughUsdSkel) {
    const Imported gltf("skinned.gltf");
    ASSERT_TRUE(gltf.stage);
    gltf.prim("/Root", "SkelRoot");
    const Prim& arm = gltf.prim("/Root/Arm/Arm", "Mesh");
    auto skinning = usda::resolveSkinning(*gltf.stage, arm);
    ASSERT_TRUE(skinning && std::holds_alternative<usda::Skinning>(*skinning));
    auto world = [&](double time) {
        std::string problem;
        auto points = usda::skinPoints(*gltf.stage, std::get<usda::Skinning>(*skinning),
                                       arm.attribute("points")->evaluate(time)->numbers, time, &problem);
        EXPECT_EQ(problem, "");
        std::vector<Vec3> out;
        auto m = gltf.stage->worldTransform(arm, time);
        for (size_t i = 0; i + 2 < points.size(); i += 3)
            out.push_back({points[i] * m[0] + points[i + 1] * m[4] + points[i + 2] * m[8] + m[12],
                           points[i] * m[1] + points[i + 1] * m[5] + points[i + 2] * m[9] + m[13],
                           points[i] * m[2] + points[i + 1] * m[6] + points[i + 2] * m[10] + m[14]});
        return out;
    };
    // The mesh's own node (100 along X) is ignored, as glTF and UsdSkel both say: the points
    // stay where the skin was bound until the elbow bends.
    const std::vector<Vec3> bound = world(0);
    ASSERT_EQ(bound.size(), 3u);
    expectNear(bound[0], {0.5, 10, 0});
    expectNear(bound[1], {2, 10, 0});
    expectNear(bound[2], {1.5, 10, 0});
    // Bent: the elbow's point swings from 1 beyond the elbow along X to 1 above it; the shared
    // point goes half way between where each joint takes it.
    const std::vector<Vec3> bent = world(1000);
    ASSERT_EQ(bent.size(), 3u);
    expectNear(bent[0], {0.5, 10, 0});
    expectNear(bent[1], {1, 11, 0});
    expectNear(bent[2], {1.25, 10.25, 0});
    EXPECT_FALSE(gltf.warned("skinning"));
}

TEST(GltfImport, PbrMaterialInputs) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string material = kLooks + "/Painted_Metal";
    const std::string surface = material + "/Surface";
    EXPECT_EQ(gltf.connection(material, "outputs:surface"), surface + ".outputs:surface");
    EXPECT_EQ(gltf.token(surface, "info:id"), "UsdPreviewSurface");
    expectNear(gltf.numbers(surface, "inputs:diffuseColor"), {0.8, 0.2, 0.1});
    expectNear(gltf.numbers(surface, "inputs:metallic"), {0.7});
    expectNear(gltf.numbers(surface, "inputs:roughness"), {0.3});
    expectNear(gltf.numbers(surface, "inputs:emissiveColor"), {0.5, 0.25, 0});
    expectNear(gltf.numbers(surface, "inputs:opacity"), {1});
}

TEST(GltfImport, BaseColorTextureIsScaledByTheBaseColorFactor) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string material = kLooks + "/Painted_Metal";
    const std::string texture = material + "/BaseColorTexture";
    const std::string reader = material + "/TexCoordReader";
    EXPECT_EQ(gltf.connection(material + "/Surface", "inputs:diffuseColor"), texture + ".outputs:rgb");
    EXPECT_EQ(gltf.token(texture, "info:id"), "UsdUVTexture");
    // Absolute, from the image's uri relative to the .gltf.
    EXPECT_EQ(gltf.token(texture, "inputs:file"), (kData / "textures/checker.png").lexically_normal().generic_string());
    EXPECT_EQ(gltf.connection(texture, "inputs:st"), reader + ".outputs:result");
    expectNear(gltf.numbers(texture, "inputs:scale"), {0.8, 0.2, 0.1, 1});
    EXPECT_EQ(gltf.token(reader, "info:id"), "UsdPrimvarReader_float2");
    EXPECT_EQ(gltf.token(reader, "inputs:varname"), "st");
}

// The Embedded material's base colour is a 1x1 PNG of (255, 128, 0) in a data: URI
// (make_scene_gltf.py): written out as a file the delegate reads like any texture.
// The material's base colour texture is an image written out of the file, bound to its surface's
// diffuseColor, one texel of `rgb`; returns the file.
std::string expectWrittenTexture(const Imported& imported, const std::string& material, std::array<float, 3> rgb) {
    const std::string texture = material + "/BaseColorTexture";
    imported.prim(texture, "Shader");
    EXPECT_EQ(imported.connection(material + "/Surface", "inputs:diffuseColor"), texture + ".outputs:rgb");
    const std::string file = imported.token(texture, "inputs:file");
    EXPECT_TRUE(file.ends_with(".png")) << file;
    auto image = image::readStbImage(file);
    EXPECT_FALSE(image::isError(image)) << image::errorOf(image);
    if (image::isError(image)) return file;
    const auto& pixels = std::get<image::Image>(image);
    EXPECT_EQ(pixels.width, 1);
    EXPECT_EQ(pixels.height, 1);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(pixels.pixels.at(size_t(c)), rgb[size_t(c)]) << "channel " << c;
    return file;
}

TEST(GltfImport, EmbeddedTexturesAreWrittenOutAndBound) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string material = kLooks + "/Embedded";
    const std::string file = expectWrittenTexture(gltf, material, {1.0f, 128.0f / 255.0f, 0.0f});
    // A second import of the same file reuses the file written.
    const Imported again("scene.gltf");
    EXPECT_EQ(again.token(material + "/BaseColorTexture", "inputs:file"), file);
    EXPECT_FALSE(gltf.warned("material 'Embedded'"));
}

// A binary glTF keeps its images in buffer views of its binary chunk: written out and bound as a
// data: URI's are (tests/import/data/make_scene_gltf.py writes embedded.glb).
TEST(GltfImport, GlbImagesInBufferViewsAreWrittenOutAndBound) {
    const Imported glb("embedded.glb");
    ASSERT_TRUE(glb.stage);
    expectWrittenTexture(glb, kLooks + "/Packed", {0.0f, 64.0f / 255.0f, 1.0f});
    EXPECT_FALSE(glb.warned("material 'Packed'"));
}

TEST(GltfImport, PerspectiveCameraKeepsTheFieldOfView) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string camera = "/Root/Main_Camera/Main_Camera";
    EXPECT_EQ(gltf.token(camera, "projection"), "perspective");
    const double focal = gltf.numbers(camera, "focalLength").at(0);
    const double width = gltf.numbers(camera, "horizontalAperture").at(0);
    const double height = gltf.numbers(camera, "verticalAperture").at(0);
    // yfov 0.8 rad, aspect ratio 1.5.
    EXPECT_NEAR(2.0 * std::atan(height / (2.0 * focal)), 0.8, 1e-6);
    EXPECT_NEAR(width / height, 1.5, 1e-6);
    expectNear(gltf.numbers(camera, "clippingRange"), {0.1, 100});
    // glTF cameras look down -Z with +Y up, as USD's do.
    expectNear(gltf.worldDirection(camera, {0, 0, -1}), {0, 0, -1});
    expectNear(gltf.worldDirection(camera, {0, 1, 0}), {0, 1, 0});
}

TEST(GltfImport, OrthographicCameraApertures) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string camera = "/Root/Ortho/Ortho";
    EXPECT_EQ(gltf.token(camera, "projection"), "orthographic");
    // xmag 2 and ymag 1 are half extents; apertures are in tenths of a scene unit.
    expectNear(gltf.numbers(camera, "horizontalAperture"), {40});
    expectNear(gltf.numbers(camera, "verticalAperture"), {20});
    expectNear(gltf.numbers(camera, "clippingRange"), {0.01, 50});
}

TEST(GltfImport, DirectionalLightShinesAlongTheSourceDirection) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string sun = "/Root/Sun/Sun";
    // The Sun node is turned -90 degrees about X: its -Z light direction points down.
    expectNear(gltf.worldDirection(sun, {0, 0, -1}), {0, -1, 0});
    expectNear(gltf.numbers(sun, "inputs:color"), {1, 0.5, 0.25});
    expectNear(gltf.numbers(sun, "inputs:intensity"), {3});
    expectNear(gltf.numbers(sun, "inputs:normalize"), {1});
}

TEST(GltfImport, PointLightIsASmallSphereOfTheSameIntensity) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    const std::string bulb = "/Root/Bulb/Bulb";
    expectNear(gltf.worldPoint(bulb, {0, 0, 0}), {0, 3, 0});
    expectNear(gltf.numbers(bulb, "treatAsPoint"), {1});
    expectNear(gltf.numbers(bulb, "inputs:color"), {1, 1, 1});
    const double radius = gltf.numbers(bulb, "inputs:radius").at(0);
    EXPECT_NEAR(radius, 0.01, 1e-9);
    // 20 candela: a sphere of radiance L gives pi * L * r^2 / d^2, a point of intensity I gives I / d^2.
    EXPECT_NEAR(gltf.numbers(bulb, "inputs:intensity").at(0) * std::acos(-1.0) * radius * radius, 20, 1e-3);
}

TEST(GltfImport, SpotLightBecomesAPointLightWithAWarning) {
    const Imported gltf("scene.gltf");
    ASSERT_TRUE(gltf.stage);
    gltf.prim("/Root/Spot/Spot", "SphereLight");
    EXPECT_TRUE(gltf.warned("light 'Spot': spot cone shaping is not supported yet"));
}

TEST(GltfImport, NonFiniteDataIsDroppedWithWarnings) {
    const Imported gltf("nonfinite.gltf");
    ASSERT_TRUE(gltf.stage);
    EXPECT_FALSE(std::regex_search(gltf.result.usda, std::regex(R"(\b(nan|inf)\b)")));
    // One primitive has a NaN normal and an infinite texture coordinate: the mesh stays without them.
    const Prim& mesh = gltf.prim("/Root/Broken_0", "Mesh");
    EXPECT_FALSE(mesh.attribute("normals"));
    EXPECT_FALSE(mesh.attribute("primvars:st"));
    EXPECT_TRUE(gltf.warned("mesh 'Broken-0': non-finite normals dropped"));
    EXPECT_TRUE(gltf.warned("mesh 'Broken-0': non-finite texture coordinates dropped"));
    // The other has a NaN point: skipped.
    EXPECT_FALSE(gltf.stage->find("/Root/Broken_1"));
    EXPECT_TRUE(gltf.warned("mesh 'Broken-1': non-finite points; mesh skipped"));
    // The key at t = 1000 moves to NaN: only t = 0 is kept, and the range ends there.
    EXPECT_TRUE(gltf.warned("animation keys with non-finite values dropped"));
    EXPECT_EQ(gltf.stage->metadata().endTimeCode, 0.0);
}

// ---- OBJ --------------------------------------------------------------------------------------

// cube.obj's positions and texture coordinates, and its polygons as (position, texcoord) corners,
// 1-based as in the file.
const std::vector<Vec3> kObjPositions = {{-1, -1, 1}, {1, -1, 1},  {1, 1, 1},  {-1, 1, 1},
                                         {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}};
const std::vector<std::array<double, 2>> kObjTexCoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const std::vector<std::vector<std::array<int, 2>>> kObjFaces = {
    {{1, 1}, {2, 2}, {3, 3}, {4, 4}}, {{6, 1}, {5, 2}, {8, 3}, {7, 4}}, {{5, 1}, {1, 2}, {4, 3}, {8, 4}},
    {{2, 1}, {6, 2}, {7, 3}, {3, 4}}, {{4, 1}, {3, 2}, {7, 3}, {8, 4}}, {{5, 1}, {6, 2}, {2, 3}},
    {{5, 1}, {2, 3}, {1, 4}}};

TEST(ObjImport, CubeCornersMatchTheSource) {
    const Imported obj("cube.obj");
    ASSERT_TRUE(obj.stage);
    const std::string cube = "/Root/Cube/Cube";
    obj.prim(cube, "Mesh");
    // Quads and triangles stay in one mesh, in the file's order.
    expectNear(obj.numbers(cube, "faceVertexCounts"), {4, 4, 4, 4, 4, 3, 3});
    const std::vector<double> indices = obj.numbers(cube, "faceVertexIndices");
    const std::vector<double> points = obj.numbers(cube, "points");
    const std::vector<double> st = obj.numbers(cube, "primvars:st");
    ASSERT_EQ(indices.size(), 26u);
    ASSERT_EQ(points.size() / 3, st.size() / 2);
    size_t corner = 0;
    for (const auto& face : kObjFaces) {
        for (const auto& [position, texCoord] : face) {
            const size_t point = static_cast<size_t>(indices.at(corner++));
            ASSERT_LT(point * 3 + 2, points.size());
            const Vec3& expectedPoint = kObjPositions.at(static_cast<size_t>(position - 1));
            const auto& expectedSt = kObjTexCoords.at(static_cast<size_t>(texCoord - 1));
            for (size_t c = 0; c < 3; ++c) EXPECT_EQ(points[point * 3 + c], expectedPoint[c]) << "corner " << corner;
            for (size_t c = 0; c < 2; ++c) EXPECT_EQ(st[point * 2 + c], expectedSt[c]) << "corner " << corner;
        }
    }
    // Every written point is used: the line's extra vertex is not written.
    std::vector<bool> used(points.size() / 3, false);
    for (const double index : indices) used.at(static_cast<size_t>(index)) = true;
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
    EXPECT_FALSE(obj.prim(cube, "Mesh").attribute("normals"));
}

TEST(ObjImport, UnitsAndDroppedLinesAreReported) {
    const Imported obj("cube.obj");
    ASSERT_TRUE(obj.stage);
    EXPECT_EQ(obj.stage->metadata().metersPerUnit, 1.0);
    EXPECT_TRUE(obj.warned("OBJ files carry no units"));
    EXPECT_TRUE(obj.warned("mesh 'Cube': 1 point and line primitives dropped"));
    EXPECT_FALSE(obj.stage->metadata().startTimeCode);
    EXPECT_EQ(obj.stage->metadata().timeCodesPerSecond, 24.0);
}

TEST(ObjImport, PhongMaterial) {
    const Imported obj("cube.obj");
    ASSERT_TRUE(obj.stage);
    const std::string material = kLooks + "/Brick";
    const std::string surface = material + "/Surface";
    expectNear(obj.numbers(surface, "inputs:diffuseColor"), {0.7, 0.3, 0.2});
    // Ns 30: roughness = (2 / (30 + 2))^(1/4).
    expectNear(obj.numbers(surface, "inputs:roughness"), {0.5});
    expectNear(obj.numbers(surface, "inputs:opacity"), {0.5});
    EXPECT_FALSE(obj.prim(surface, "Shader").attribute("inputs:metallic"));
    const std::string texture = material + "/BaseColorTexture";
    EXPECT_EQ(obj.token(texture, "inputs:file"), (kData / "textures/brick.png").lexically_normal().generic_string());
    EXPECT_EQ(obj.connection(surface, "inputs:diffuseColor"), texture + ".outputs:rgb");
    // A Phong diffuse texture replaces the diffuse colour rather than being scaled by it.
    EXPECT_FALSE(obj.prim(texture, "Shader").attribute("inputs:scale"));
    const usda::Relationship* binding = obj.prim("/Root/Cube/Cube", "Mesh").relationship("material:binding");
    ASSERT_TRUE(binding);
    EXPECT_EQ(binding->targets, std::vector<std::string>{material});
}

// ---- FBX --------------------------------------------------------------------------------------

TEST(FbxImport, UnitScaleFactorGivesMetersPerUnit) {
    const Imported fbx("scene.fbx");
    ASSERT_TRUE(fbx.stage);
    // UnitScaleFactor 2.54: inches.
    EXPECT_NEAR(fbx.stage->metadata().metersPerUnit, 0.0254, 1e-12);
}

TEST(FbxImport, ZUpSceneIsTurnedYUp) {
    const Imported fbx("scene.fbx");
    ASSERT_TRUE(fbx.stage);
    const std::string shape = "/Root/Group/Shape/Shape";
    expectNear(fbx.numbers(shape, "faceVertexCounts"), {4, 3});
    expectNear(fbx.numbers(shape, "faceVertexIndices"), {0, 1, 2, 3, 1, 4, 2});
    expectNear(fbx.numbers(shape, "points"), flatten({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}}));
    // (0,1,0) in Shape (0,5,0) in Group (10,0,0) is (10,6,0) in the Z-up file: (10,0,-6) Y-up.
    expectNear(fbx.worldPoint(shape, {0, 1, 0}), {10, 0, -6});
    expectNear(fbx.worldPoint(shape, {0, 0, 1}), {10, 1, -5});
}

TEST(FbxImport, CameraLooksDownTheFilesXAxis) {
    const Imported fbx("scene.fbx");
    ASSERT_TRUE(fbx.stage);
    const std::string camera = "/Root/Lens/Lens";
    fbx.prim(camera, "Camera");
    // At (0,-20,0) in the file; FBX cameras look down their +X.
    expectNear(fbx.worldPoint(camera, {0, 0, 0}), {0, 0, 20});
    expectNear(fbx.worldDirection(camera, {0, 0, -1}), {1, 0, 0});
    const double focal = fbx.numbers(camera, "focalLength").at(0);
    const double width = fbx.numbers(camera, "horizontalAperture").at(0);
    const double height = fbx.numbers(camera, "verticalAperture").at(0);
    // FieldOfView 60 degrees, 320 x 200.
    EXPECT_NEAR(2.0 * std::atan(width / (2.0 * focal)), std::acos(-1.0) / 3.0, 1e-6);
    EXPECT_NEAR(width / height, 1.6, 1e-6);
    expectNear(fbx.numbers(camera, "clippingRange"), {5, 500});
}

TEST(FbxImport, PointLightAndPhongMaterial) {
    const Imported fbx("scene.fbx");
    ASSERT_TRUE(fbx.stage);
    const std::string lamp = "/Root/Lamp/Lamp";
    fbx.prim(lamp, "SphereLight");
    expectNear(fbx.worldPoint(lamp, {0, 0, 0}), {0, 30, 0});
    // Colour (1, 0.5, 0.5) at Intensity 200 (percent).
    expectNear(fbx.numbers(lamp, "inputs:color"), {1, 0.5, 0.5});
    const double radius = fbx.numbers(lamp, "inputs:radius").at(0);
    EXPECT_NEAR(radius * 0.0254, 0.01, 1e-6);
    EXPECT_NEAR(fbx.numbers(lamp, "inputs:intensity").at(0) * std::acos(-1.0) * radius * radius, 2, 1e-4);

    const std::string surface = kLooks + "/Clay/Surface";
    expectNear(fbx.numbers(surface, "inputs:diffuseColor"), {0.6, 0.4, 0.2});
    // Assimp derives FBX roughness from ShininessExponent 6 as Blender does: 1 - sqrt(6) / 10.
    expectNear(fbx.numbers(surface, "inputs:roughness"), {1 - std::sqrt(6.0) / 10});
}

// ---- Errors and formats -----------------------------------------------------------------------

TEST(AssimpImport, MissingFileIsAnErrorNamingIt) {
    const std::filesystem::path missing = kData / "no_such_scene.gltf";
    auto result = importWithAssimp(missing);
    ASSERT_TRUE(std::holds_alternative<ImportError>(result));
    EXPECT_NE(std::get<ImportError>(result).message.find(missing.string()), std::string::npos)
        << std::get<ImportError>(result).message;
}

TEST(AssimpImport, CorruptFileIsAnErrorNamingIt) {
    const std::filesystem::path corrupt = kData / "corrupt.gltf";
    auto result = importWithAssimp(corrupt);
    ASSERT_TRUE(std::holds_alternative<ImportError>(result));
    const std::string& message = std::get<ImportError>(result).message;
    EXPECT_NE(message.find(corrupt.string()), std::string::npos) << message;
    // Assimp's reason follows the file name.
    EXPECT_GT(message.size(), message.find(corrupt.string()) + corrupt.string().size() + 2) << message;
}

// Assimp decodes corrupt base64 into garbage without a word; the harness names the URI's place.
TEST(AssimpImport, CorruptBase64BufferIsAnErrorNamingTheUri) {
    const std::filesystem::path file = kData / "bad_base64.gltf";
    auto result = importWithAssimp(file);
    ASSERT_TRUE(std::holds_alternative<ImportError>(result));
    EXPECT_EQ(std::get<ImportError>(result).message,
              file.string() + ":11:25: buffers[0].uri: base64 data has '!' at offset 20, which base64 does not use");
}

TEST(AssimpImport, ShortBase64BufferIsAnError) {
    // corrupt.gltf's buffer says 12 bytes but "AAAA" holds 3.
    auto result = importWithAssimp(kData / "corrupt.gltf");
    ASSERT_TRUE(std::holds_alternative<ImportError>(result));
    EXPECT_NE(std::get<ImportError>(result).message.find("buffers[0].uri: base64 data holds 3 bytes but byteLength is 12"),
              std::string::npos)
        << std::get<ImportError>(result).message;
}

// A .gltf whose first bytes are a Quick3D header (found by fuzz_import): Assimp would offer it to
// its Quick3D reader too, which crashes on it. Only the glTF readers see it, and they refuse it.
// Imported in this process on purpose: a reader crash would end the test.
TEST(AssimpImport, AFileIsReadOnlyByTheReadersOfItsExtension) {
    const std::filesystem::path file = kData / "quick3d_header.gltf";
    auto result = importInThisProcess(file);
    ASSERT_TRUE(std::holds_alternative<ImportError>(result));
    const ImportError& error = std::get<ImportError>(result);
    EXPECT_EQ(error.crash, ImportError::Crash::None);
    EXPECT_EQ(error.message.rfind("cannot import " + file.string() + ": ", 0), 0u) << error.message;
    // Where the Quick3D reader does not crash, it refuses the file in its own words.
    EXPECT_EQ(error.message.find("Quick3D"), std::string::npos) << error.message;
}

// The harness imports in a child process: the same result as in this process, and the embedded
// images the child wrote are this process's to reuse.
TEST(AssimpImport, TheImportInAChildProcessAnswersAsInThisOne) {
    for (const char* name : {"scene.gltf", "scene.fbx", "cube.obj", "skinned.gltf", "nonfinite.gltf"}) {
        auto child = importWithAssimp(kData / name);
        auto here = importInThisProcess(kData / name);
        ASSERT_TRUE(std::holds_alternative<ImportResult>(child)) << name << ": " << std::get<ImportError>(child).message;
        ASSERT_TRUE(std::holds_alternative<ImportResult>(here)) << name;
        EXPECT_EQ(std::get<ImportResult>(child).usda, std::get<ImportResult>(here).usda) << name;
        EXPECT_EQ(std::get<ImportResult>(child).warnings, std::get<ImportResult>(here).warnings) << name;
    }
    for (const char* name : {"corrupt.gltf", "bad_base64.gltf", "quick3d_header.gltf", "no_such_scene.obj"}) {
        auto child = importWithAssimp(kData / name);
        auto here = importInThisProcess(kData / name);
        ASSERT_TRUE(std::holds_alternative<ImportError>(child)) << name;
        ASSERT_TRUE(std::holds_alternative<ImportError>(here)) << name;
        EXPECT_EQ(std::get<ImportError>(child).message, std::get<ImportError>(here).message) << name;
        EXPECT_EQ(std::get<ImportError>(child).crash, ImportError::Crash::None) << name;
    }
}

// A relative path is relative to this process's working folder, also in the child, and messages
// name the file as given.
TEST(AssimpImport, ARelativePathMeansWhatItMeansInThisProcess) {
    const std::filesystem::path before = std::filesystem::current_path();
    std::filesystem::current_path(kData);
    auto found = importWithAssimp("cube.obj");
    auto missing = importWithAssimp("no_such_scene.obj");
    std::filesystem::current_path(before);
    EXPECT_TRUE(std::holds_alternative<ImportResult>(found));
    ASSERT_TRUE(std::holds_alternative<ImportError>(missing));
    EXPECT_EQ(std::get<ImportError>(missing).message.rfind("cannot import no_such_scene.obj: ", 0), 0u)
        << std::get<ImportError>(missing).message;
}

TEST(AssimpImport, FormatsByExtension) {
    for (const char* name : {"a.gltf", "a.glb", "a.fbx", "a.obj", "A.GLTF", "dir/b.Glb", "C.FBX", "d.OBJ"})
        EXPECT_TRUE(isAssimpFormat(name)) << name;
    for (const char* name : {"a.usda", "a.usd", "a.dae", "a.obj.txt", "gltf", "a", ""})
        EXPECT_FALSE(isAssimpFormat(name)) << name;
    auto result = importWithAssimp(kData / "scene.usda");
    ASSERT_TRUE(std::holds_alternative<ImportError>(result));
    EXPECT_NE(std::get<ImportError>(result).message.find("scene.usda"), std::string::npos);
}

}  // namespace
}  // namespace obscura::harness
