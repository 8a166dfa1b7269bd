// GeomSubsets in a USD stage, served by the harness's scene host as their mesh's material subsets:
// which subsets count (familyName materialBind, elementType face, a binding of their own), and a
// reload that edits a subset marks its mesh dirty, as a viewer's reload does. The albedo AOV
// shows which material each half of a two-face mesh drew with.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

namespace obscura::test {
namespace {

std::string material(const std::string& name, const std::string& colour) {
    return "    def Material \"" + name + "\"\n    {\n        token outputs:surface.connect = </Materials/" + name +
           "/Surface.outputs:surface>\n        def Shader \"Surface\"\n        {\n"
           "            uniform token info:id = \"UsdPreviewSurface\"\n            color3f inputs:diffuseColor = " +
           colour + "\n            token outputs:surface\n        }\n    }\n";
}

std::string subset(const std::string& name, const std::string& indices, const std::string& binding,
                   const std::string& family = "materialBind", const std::string& elementType = "face") {
    return "    def GeomSubset \"" + name + "\" (\n        prepend apiSchemas = [\"MaterialBindingAPI\"]\n    )\n    {\n"
           "        uniform token elementType = \"" + elementType + "\"\n        uniform token familyName = \"" + family +
           "\"\n        int[] indices = " + indices + "\n" +
           (binding.empty() ? "" : "        rel material:binding = <" + binding + ">\n") + "    }\n";
}

// Face 0 is the left half of the view, face 1 the right half; the mesh itself is bound to blue.
std::string halvesStage(const std::string& subsets) {
    return std::string("#usda 1.0\n") +
           "def Camera \"Camera\"\n{\n    float focalLength = 50\n    float horizontalAperture = 20.955\n"
           "    float verticalAperture = 20.955\n    float2 clippingRange = (0.1, 100)\n"
           "    double3 xformOp:translate = (0, 0, 5)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n"
           "def Scope \"Materials\"\n{\n" +
           material("Red", "(0.8, 0.05, 0.05)") + material("Green", "(0.05, 0.8, 0.05)") +
           material("Blue", "(0.05, 0.05, 0.8)") +
           "}\n"
           "def Mesh \"Halves\" (\n    prepend apiSchemas = [\"MaterialBindingAPI\"]\n)\n{\n"
           "    point3f[] points = [(-1.2, -1.2, 0), (0, -1.2, 0), (1.2, -1.2, 0), (-1.2, 1.2, 0), (0, 1.2, 0), (1.2, 1.2, 0)]\n"
           "    int[] faceVertexCounts = [4, 4]\n    int[] faceVertexIndices = [0, 1, 4, 3, 1, 2, 5, 4]\n"
           "    uniform token subdivisionScheme = \"none\"\n    rel material:binding = </Materials/Blue>\n"
           "    uniform token subsetFamily:materialBind:familyType = \"partition\"\n" +
           subsets + "}\n";
}

using Rgb = std::array<float, 3>;
const Rgb kRed{0.8f, 0.05f, 0.05f}, kGreen{0.05f, 0.8f, 0.05f}, kBlue{0.05f, 0.05f, 0.8f};

// Which material the left and right halves drew with.
void expectHalves(const std::vector<float>& albedo, const Rgb& left, const Rgb& right) {
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    for (auto [x, expected] : {std::pair{16, left}, {48, right}})
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(albedo[(size_t(32) * kWidth + size_t(x)) * 3 + c], expected[c], 0.02f) << "x " << x << " channel " << c;
}

TEST(GeomSubsetStage, MaterialBindSubsetsBindTheirFaces) {
    HostedStage scene(usda::Stage::openFromString(
        halvesStage(subset("Left", "[0]", "/Materials/Red") + subset("Right", "[1]", "/Materials/Green") +
                    // Another family, and a subset of edges: neither binds faces.
                    subset("Uvs", "[0, 1]", "/Materials/Blue", "uvIslands") +
                    subset("Edges", "[0]", "/Materials/Blue", "materialBind", "edge")),
        "halves.usda"));
    expectHalves(scene.renderAlbedo(), kRed, kGreen);
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
}

TEST(GeomSubsetStage, ASubsetWithoutABindingOfItsOwnTakesTheMeshs) {
    HostedStage scene(usda::Stage::openFromString(
        halvesStage(subset("Left", "[0]", "") + subset("Right", "[1]", "/Materials/Green")), "halves.usda"));
    expectHalves(scene.renderAlbedo(), kBlue, kGreen);
}

TEST(GeomSubsetStage, BadIndicesAreLocatedOnTheSubset) {
    const std::string text =
        halvesStage(subset("Left", "[0, 5]", "/Materials/Red") + subset("Right", "[1]", "/Materials/Green"));
    HostedStage scene(usda::Stage::openFromString(text, "halves.usda"));
    expectHalves(scene.renderAlbedo(), kRed, kGreen);
    // The plugin names the subset and its attribute first (material_subsets_test.cpp checks the
    // message), so the host locates it where the subset's indices are authored.
    auto message = harness::parsePrimMessage("/Halves/Left: indices[1] = 5 is outside the mesh's 2 faces; ignored");
    ASSERT_TRUE(message.has_value());
    auto where = scene.host->locate(*message);
    ASSERT_TRUE(where.has_value());
    const size_t offset = text.find("int[] indices = [0, 5]");
    EXPECT_EQ(where->line, 1 + int(std::count(text.begin(), text.begin() + long(offset), '\n')));
}

// A viewer's reload (harness/view/scene_reload.cpp): the new stage's host marks dirty only what
// changed, and the delegate keeps pulling through one scene delegate that answers with the
// current host.
struct ReloadableScene {
    static ObscuraStatus getValue(void* user, const char* path, const char* attribute, double time, ObscuraValue* out) {
        const ObscuraSceneDelegate& current = static_cast<ReloadableScene*>(user)->host->sceneDelegate();
        return current.getValue(current.userData, path, attribute, time, out);
    }
    static ObscuraStatus getInterpolation(void* user, const char* path, const char* attribute, ObscuraInterpolation* out) {
        const ObscuraSceneDelegate& current = static_cast<ReloadableScene*>(user)->host->sceneDelegate();
        return current.getInterpolation(current.userData, path, attribute, out);
    }
    static ObscuraStatus sampleTransform(void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                         double* times, double* matrices, uint32_t* count) {
        const ObscuraSceneDelegate& current = static_cast<ReloadableScene*>(user)->host->sceneDelegate();
        return current.sampleTransform(current.userData, path, t0, t1, maxSamples, times, matrices, count);
    }

    explicit ReloadableScene(const std::string& text) : scene(usda::Stage::openFromString(text, "halves.usda")) {
        host = &*scene.host;
        buffer = scene.host->addRenderBuffer(scene.api(), scene.delegate, "albedo", kWidth, kHeight);
        forwarding = {OBSCURA_STRUCTURE_TYPE_SCENE_DELEGATE, nullptr, sizeof(forwarding), 0, this,
                      &getValue, &getInterpolation, &sampleTransform};
        EXPECT_EQ(scene.api().setSceneDelegate(scene.delegate, &forwarding), OBSCURA_OK);
    }
    // Reads `text` as the edited file and adopts its changes; returns the prims touched.
    size_t reload(const std::string& text) {
        auto opened = usda::Stage::openFromString(text, "halves.usda");
        stages.push_back(std::move(std::get<std::unique_ptr<usda::Stage>>(opened)));
        hosts.push_back(std::make_unique<harness::UsdSceneHost>(*stages.back()));
        size_t touched = 0;
        EXPECT_EQ(hosts.back()->adoptChanges(*host, scene.api(), scene.delegate, 0.0, touched), OBSCURA_OK);
        host = hosts.back().get();
        return touched;
    }
    std::vector<float> renderAlbedo() {
        ObscuraAovBinding binding{"albedo", buffer.c_str()};
        ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC, nullptr, sizeof(desc), "/Camera", {0, 0, 0, 0},
                                   0.0, 1, &binding};
        EXPECT_EQ(scene.api().render(scene.delegate, &desc), OBSCURA_OK) << scene.api().lastError(scene.delegate);
        ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
        if (scene.api().mapRenderBuffer(scene.delegate, buffer.c_str(), &mapped) != OBSCURA_OK) return {};
        const auto* p = static_cast<const float*>(mapped.data);
        std::vector<float> out(p, p + size_t(mapped.width) * mapped.height * 3);
        scene.api().unmapRenderBuffer(scene.delegate, buffer.c_str());
        return out;
    }

    // Every reload's stage and host, alive until the delegate that pulls from them is gone.
    std::vector<std::unique_ptr<usda::Stage>> stages;
    std::vector<std::unique_ptr<harness::UsdSceneHost>> hosts;
    HostedStage scene;
    const harness::UsdSceneHost* host = nullptr;
    std::string buffer;
    ObscuraSceneDelegate forwarding{};
};

TEST(GeomSubsetStage, EditingASubsetMarksItsMeshDirty) {
    const std::string before = subset("Left", "[0]", "/Materials/Red") + subset("Right", "[1]", "/Materials/Green");
    ReloadableScene scene(halvesStage(before));
    expectHalves(scene.renderAlbedo(), kRed, kGreen);

    // A subset's binding.
    const std::string rebound = subset("Left", "[0]", "/Materials/Red") + subset("Right", "[1]", "/Materials/Blue");
    EXPECT_EQ(scene.reload(halvesStage(rebound)), 1u) << "the mesh, not its subsets, is the prim";
    expectHalves(scene.renderAlbedo(), kRed, kBlue);

    // A subset's faces.
    const std::string moved = subset("Left", "[1]", "/Materials/Red") + subset("Right", "[0]", "/Materials/Blue");
    EXPECT_EQ(scene.reload(halvesStage(moved)), 1u);
    expectHalves(scene.renderAlbedo(), kBlue, kRed);

    // Unchanged: nothing to do.
    EXPECT_EQ(scene.reload(halvesStage(moved)), 0u);
}

}  // namespace
}  // namespace obscura::test
