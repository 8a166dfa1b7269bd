// Per-face materials through material subsets (UsdGeomSubset, familyName materialBind, served
// as the mesh's materialSubsets:* attributes): each subset's faces draw with its material, the
// faces of none with the mesh's, a subdivided surface stays whole, instanced prototypes keep their
// subsets, edits re-sync, and bad subsets are reported with the prim and the index. The albedo
// AOV shows which material a pixel drew with (no lights needed).
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace obscura::test {
namespace {

using Rgb = std::array<float, 3>;
const Rgb kRed{0.8f, 0.05f, 0.05f};
const Rgb kGreen{0.05f, 0.8f, 0.05f};
const Rgb kBlue{0.05f, 0.05f, 0.8f};
const Rgb kFallbackGrey{0.18f, 0.18f, 0.18f};
constexpr float kHalf = 1.2f;  // beyond the view's half-size at z = 0 (1.04775)

// Points: bottom row left to right (0, 1, 2), top row (3, 4, 5); face 0 is the left half, face 1
// the right half of the view of a camera at (0, 0, 5) looking down -Z.
std::map<std::string, HostValue> halves(float half = kHalf) {
    return {{"points", HostValue::points({{-half, -half, 0}, {0, -half, 0}, {half, -half, 0},
                                          {-half, half, 0}, {0, half, 0}, {half, half, 0}})},
            {"faceVertexCounts", HostValue::intArray({4, 4})},
            {"faceVertexIndices", HostValue::intArray({0, 1, 4, 3, 1, 2, 5, 4})},
            {"subdivisionScheme", HostValue::token("none")}};
}

std::map<std::string, HostValue> withSubsets(std::map<std::string, HostValue> mesh, std::vector<int32_t> counts,
                                             std::vector<int32_t> indices, std::vector<std::string> materials) {
    mesh["materialSubsets:faceCounts"] = HostValue::intArray(counts);
    mesh["materialSubsets:faceIndices"] = HostValue::intArray(indices);
    mesh["materialSubsets:materials"] = HostValue::paths(materials);
    return mesh;
}

struct SubsetScene {
    TestHost host;
    SubsetScene() {
        host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
        addMaterial(host, "/Materials/Red", kRed);
        addMaterial(host, "/Materials/Green", kGreen);
        addMaterial(host, "/Materials/Blue", kBlue);
        host.addRenderBuffer("/Buffers/albedo", "float32Vec3", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/id", "int32", kWidth, kHeight);
        host.addRenderBuffer("/Buffers/depth", "float32", kWidth, kHeight);
    }
    void render(const std::string& camera = "/Camera") {
        ASSERT_EQ(host.render(camera, {{"albedo", "/Buffers/albedo"}, {"primId", "/Buffers/id"},
                                       {"depth", "/Buffers/depth"}}),
                  OBSCURA_OK)
            << host.lastError();
        albedo = host.readFloats("/Buffers/albedo");
        ids = host.readInts("/Buffers/id");
        depth = host.readFloats("/Buffers/depth");
    }
    Rgb albedoAt(int x, int y) const {
        const float* p = &albedo[(size_t(y) * kWidth + size_t(x)) * 3];
        return {p[0], p[1], p[2]};
    }
    int32_t idAt(int x, int y) const { return ids[size_t(y) * kWidth + size_t(x)]; }
    bool warned(const std::string& fragment) const {
        const auto& warnings = host.loggedWarnings();
        return std::any_of(warnings.begin(), warnings.end(),
                           [&](const std::string& w) { return w.find(fragment) != std::string::npos; });
    }
    std::vector<float> albedo, depth;
    std::vector<int32_t> ids;
};

// The G-buffer keeps albedo as 8-bit sRGB: within two codes at these values.
void expectAlbedo(const SubsetScene& s, int x, int y, const Rgb& expected) {
    const Rgb got = s.albedoAt(x, y);
    for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], expected[c], 0.02f) << "pixel (" << x << ", " << y << ") channel " << c;
}

TEST(MaterialSubsets, EachSubsetsFacesDrawWithItsMaterial) {
    SubsetScene s;
    auto mesh = withSubsets(halves(), {1, 1}, {0, 1}, {"/Materials/Red", "/Materials/Green"});
    mesh["material:binding"] = HostValue::path("/Materials/Blue");
    s.host.addPrim("mesh", "/Halves", mesh);
    s.render();
    for (auto [x, y] : {std::pair{4, 8}, {28, 56}}) expectAlbedo(s, x, y, kRed);
    for (auto [x, y] : {std::pair{36, 8}, {60, 56}}) expectAlbedo(s, x, y, kGreen);
    // One prim, however many materials: both halves pick it.
    int32_t id = -1;
    ASSERT_EQ(s.host.api().getPrimId(s.host.delegate(), "/Halves", &id), OBSCURA_OK);
    EXPECT_EQ(s.idAt(8, 32), id);
    EXPECT_EQ(s.idAt(56, 32), id);
    EXPECT_EQ(renderStats(s.host).trianglesDrawn, 4u) << "each triangle drawn once";
    EXPECT_TRUE(s.host.loggedWarnings().empty()) << s.host.loggedWarnings().front();
}

TEST(MaterialSubsets, FacesInNoSubsetDrawWithTheMeshsMaterial) {
    SubsetScene s;
    auto bound = withSubsets(halves(), {1}, {1}, {"/Materials/Green"});
    bound["material:binding"] = HostValue::path("/Materials/Blue");
    s.host.addPrim("mesh", "/Bound", bound);
    s.render();
    expectAlbedo(s, 16, 32, kBlue);
    expectAlbedo(s, 48, 32, kGreen);

    // Without a binding of its own, the rest of the mesh draws with the fallback material.
    SubsetScene unbound;
    unbound.host.addPrim("mesh", "/Unbound", withSubsets(halves(), {1}, {1}, {"/Materials/Green"}));
    unbound.render();
    expectAlbedo(unbound, 16, 32, kFallbackGrey);
    expectAlbedo(unbound, 48, 32, kGreen);
}

// A curved Catmull-Clark surface over a 2 x 2 grid of faces (its centre point raised), smaller than
// the view: faces 0 (bottom left) and 3 (top right) red, 1 and 2 green. Splitting the control mesh
// would refine two surfaces with a boundary between them; the refined triangles are split instead.
std::map<std::string, HostValue> curvedGrid() {
    std::vector<std::array<float, 3>> points;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            points.push_back({-0.8f + 0.8f * float(column), -0.8f + 0.8f * float(row), row == 1 && column == 1 ? 0.6f : 0.0f});
    std::vector<int32_t> indices;
    for (int row = 0; row < 2; ++row)
        for (int column = 0; column < 2; ++column) {
            const int32_t corner = row * 3 + column;
            indices.insert(indices.end(), {corner, corner + 1, corner + 4, corner + 3});
        }
    return {{"points", HostValue::points(points)},
            {"faceVertexCounts", HostValue::intArray({4, 4, 4, 4})},
            {"faceVertexIndices", HostValue::intArray(indices)},
            {"obscura:refineLevel", HostValue::intValue(3)}};
}

TEST(MaterialSubsets, ASubdividedMeshKeepsOneSurface) {
    SubsetScene whole;
    auto plain = curvedGrid();
    plain["material:binding"] = HostValue::path("/Materials/Blue");
    whole.host.addPrim("mesh", "/Grid", plain);
    whole.render();

    SubsetScene split;
    split.host.addPrim("mesh", "/Grid",
                       withSubsets(curvedGrid(), {2, 2}, {0, 3, 1, 2}, {"/Materials/Red", "/Materials/Green"}));
    split.render();
    // The same limit surface: the same depth everywhere, no pixel through a crack between the parts.
    ASSERT_EQ(split.depth.size(), whole.depth.size());
    size_t covered = 0;
    for (size_t i = 0; i < whole.depth.size(); ++i) {
        EXPECT_EQ(split.ids[i] >= 0, whole.ids[i] >= 0) << "pixel " << i;
        EXPECT_NEAR(split.depth[i], whole.depth[i], 1e-6f) << "pixel " << i;
        covered += whole.ids[i] >= 0 ? 1 : 0;
    }
    EXPECT_GT(covered, size_t(kWidth * kHeight / 3)) << "the surface fills much of the view";
    EXPECT_LT(covered, size_t(kWidth * kHeight)) << "and has edges inside it";
    // Each control face's region has its material: quadrant centres, rows from the top.
    expectAlbedo(split, 20, 44, kRed);
    expectAlbedo(split, 44, 44, kGreen);
    expectAlbedo(split, 20, 20, kGreen);
    expectAlbedo(split, 44, 20, kRed);
    EXPECT_EQ(renderStats(split.host).trianglesDrawn, renderStats(whole.host).trianglesDrawn);
}

// An orthographic camera: one scene unit = 8 pixels of a 64x64 image, centred on the origin.
TEST(MaterialSubsets, AnInstancedPrototypeKeepsItsSubsets) {
    SubsetScene s;
    s.host.addPrim("camera", "/Ortho",
                   {{"projection", HostValue::token("orthographic")},
                    {"horizontalAperture", HostValue::floatValue(80.0f)},
                    {"verticalAperture", HostValue::floatValue(80.0f)},
                    {"clippingRange", HostValue::float2(0.1f, 100.0f)}},
                   translation(0, 0, 10));
    auto prototype = withSubsets(halves(1.0f), {1, 1}, {0, 1}, {"/Materials/Red", "/Materials/Green"});
    prototype["material:binding"] = HostValue::path("/Materials/Blue");
    s.host.addPrim("mesh", "/Instancer/Prototypes/Halves", prototype);
    s.host.addPrim("instancer", "/Instancer",
                   {{"prototypes", HostValue::paths({"/Instancer/Prototypes/Halves"})},
                    {"protoIndices", HostValue::intArray({0, 0})},
                    {"positions", HostValue::points({{-2, 0, 0}, {2, 0, 0}})}});
    s.render("/Ortho");
    auto pixel = [](double x) { return int(std::floor(x * 8 + 32)); };
    for (double centre : {-2.0, 2.0}) {
        expectAlbedo(s, pixel(centre - 0.5), 29, kRed);
        expectAlbedo(s, pixel(centre + 0.5), 29, kGreen);
    }
    EXPECT_EQ(s.idAt(pixel(0.0), 29), -1) << "the prototype draws only through its instances";
}

TEST(MaterialSubsets, EditsOfASubsetReSync) {
    SubsetScene s;
    s.host.addPrim("mesh", "/Halves", withSubsets(halves(), {1, 1}, {0, 1}, {"/Materials/Red", "/Materials/Green"}));
    s.render();
    expectAlbedo(s, 16, 32, kRed);
    expectAlbedo(s, 48, 32, kGreen);

    // The subsets' bindings: the material id alone.
    s.host.set("/Halves", "materialSubsets:materials", HostValue::paths({"/Materials/Green", "/Materials/Blue"}));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Halves", OBSCURA_DIRTY_MATERIAL_ID), OBSCURA_OK);
    s.render();
    expectAlbedo(s, 16, 32, kGreen);
    expectAlbedo(s, 48, 32, kBlue);

    // Their faces: the topology.
    s.host.set("/Halves", "materialSubsets:faceIndices", HostValue::intArray({1, 0}));
    ASSERT_EQ(s.host.api().markDirty(s.host.delegate(), "/Halves", OBSCURA_DIRTY_TOPOLOGY), OBSCURA_OK);
    s.render();
    expectAlbedo(s, 16, 32, kBlue);
    expectAlbedo(s, 48, 32, kGreen);
}

TEST(MaterialSubsets, BadIndicesAreReportedWithTheSubsetAndTheIndex) {
    SubsetScene s;
    auto mesh = withSubsets(halves(), {3, 1}, {0, 7, -1, 1}, {"/Materials/Red", "/Materials/Green"});
    mesh["materialSubsets:paths"] = HostValue::paths({"/Halves/Red", "/Halves/Green"});
    s.host.addPrim("mesh", "/Halves", mesh);
    s.render();
    EXPECT_TRUE(s.warned("/Halves/Red: indices[1] = 7 is outside the mesh's 2 faces; ignored"));
    EXPECT_TRUE(s.warned("/Halves/Red: indices[2] = -1 is outside the mesh's 2 faces; ignored"));
    // The good indices still draw.
    expectAlbedo(s, 16, 32, kRed);
    expectAlbedo(s, 48, 32, kGreen);

    // Without the subsets' paths, the mesh and the subset's number.
    SubsetScene unnamed;
    unnamed.host.addPrim("mesh", "/Halves", withSubsets(halves(), {2}, {1, 2}, {"/Materials/Green"}));
    unnamed.render();
    EXPECT_TRUE(unnamed.warned("/Halves: material subset 0: indices[1] = 2 is outside the mesh's 2 faces; ignored"));
    expectAlbedo(unnamed, 48, 32, kGreen);
}

TEST(MaterialSubsets, OverlapsAndGapsAreReportedWhereTheFamilyForbidsThem) {
    auto overlapping = withSubsets(halves(), {1, 1}, {0, 0}, {"/Materials/Red", "/Materials/Green"});
    overlapping["materialSubsets:paths"] = HostValue::paths({"/Halves/Red", "/Halves/Green"});
    overlapping["material:binding"] = HostValue::path("/Materials/Blue");
    {
        SubsetScene s;
        overlapping["subsetFamily:materialBind:familyType"] = HostValue::token("partition");
        s.host.addPrim("mesh", "/Halves", overlapping);
        s.render();
        EXPECT_TRUE(s.warned("/Halves/Green: indices[0] = 0 is also in /Halves/Red, which a partition family forbids"));
        EXPECT_TRUE(s.warned("/Halves: subsetFamily:materialBind:familyType is partition but 1 of the 2 faces"));
        expectAlbedo(s, 16, 32, kRed);   // the first subset keeps the face
        expectAlbedo(s, 48, 32, kBlue);  // the face of none: the mesh's binding
    }
    {
        // Unrestricted families may overlap: the first subset still wins, silently.
        SubsetScene s;
        overlapping["subsetFamily:materialBind:familyType"] = HostValue::token("unrestricted");
        s.host.addPrim("mesh", "/Halves", overlapping);
        s.render();
        EXPECT_TRUE(s.host.loggedWarnings().empty()) << s.host.loggedWarnings().front();
        expectAlbedo(s, 16, 32, kRed);
    }
}

TEST(MaterialSubsets, ASubsetBoundToNoMaterialDrawsWithTheFallback) {
    SubsetScene s;
    auto mesh = withSubsets(halves(), {1, 1}, {0, 1}, {"/Materials/Red", "/Materials/Nowhere"});
    mesh["materialSubsets:paths"] = HostValue::paths({"/Halves/Red", "/Halves/Nowhere"});
    s.host.addPrim("mesh", "/Halves", mesh);
    s.render();
    EXPECT_TRUE(s.warned("/Halves/Nowhere: material:binding names /Materials/Nowhere, which is not a material"));
    expectAlbedo(s, 16, 32, kRed);
    expectAlbedo(s, 48, 32, kFallbackGrey);
}

TEST(MaterialSubsets, CountsThatDoNotAddUpDropTheSubsetsNotTheMesh) {
    SubsetScene s;
    auto mesh = withSubsets(halves(), {1, 2}, {0, 1}, {"/Materials/Red", "/Materials/Green"});
    mesh["material:binding"] = HostValue::path("/Materials/Blue");
    s.host.addPrim("mesh", "/Halves", mesh);
    s.render();
    EXPECT_TRUE(s.warned("/Halves: materialSubsets:faceCounts sum to 3 but materialSubsets:faceIndices has 2 entries"));
    expectAlbedo(s, 16, 32, kBlue);
    expectAlbedo(s, 48, 32, kBlue);
}

}  // namespace
}  // namespace obscura::test
