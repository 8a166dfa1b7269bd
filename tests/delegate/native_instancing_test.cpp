// USD's native instancing through the harness's scene host (harness/native_instancing.h):
// instanceable references with the same arcs share one prototype, whose geometry the plugin
// receives once and draws at every instance through one instancer. The same stage with
// instanceable = false draws the same image; picking names the instance; instances that differ in
// what their roots hand down, or whose transform shears, are not merged.
#include "tests/delegate/hosted_stage.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

namespace obscura::test {
namespace {

// A camera at z = 5 whose view fills [-1.04775, 1.04775]^2 at z = 0, a sun, and an asymmetric
// arrow (so that turns and mirrors show) as the referenced asset.
const std::string kStage = "#usda 1.0\n" + usdaCamera() + R"(def DistantLight "Sun"
{
    float inputs:intensity = 2
    float3 xformOp:rotateXYZ = (-30, 20, 0)
    uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
}
class "Arrow"
{
    def Mesh "Geom"
    {
        point3f[] points = [(-0.3, -0.1, 0), (0.1, -0.1, 0), (0.1, -0.25, 0), (0.35, 0, 0.1), (0.1, 0.25, 0), (0.1, 0.1, 0), (-0.3, 0.1, 0)]
        int[] faceVertexCounts = [7]
        int[] faceVertexIndices = [0, 1, 2, 3, 4, 5, 6]
        color3f[] primvars:displayColor = [(0.8, 0.5, 0.2)]
        uniform token subdivisionScheme = "none"
    }
}
class "Square"
{
    def Mesh "Geom"
    {
        point3f[] points = [(-0.1, -0.1, 0), (0.1, -0.1, 0), (0.1, 0.1, 0), (-0.1, 0.1, 0)]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        uniform token subdivisionScheme = "none"
    }
}
)";

// `name` referencing `asset` with `ops` (xformOp lines, their xformOpOrder included).
std::string instance(const std::string& name, const std::string& asset, bool instanceable, const std::string& ops,
                     const std::string& extra = "") {
    return "def Xform \"" + name + "\" (\n    instanceable = " + (instanceable ? "true" : "false") +
           "\n    references = </" + asset + ">\n)\n{\n" + ops + extra + "}\n";
}

std::string translate(double x, double y, const std::string& more = "", const std::string& moreOrder = "") {
    return "    double3 xformOp:translate = (" + std::to_string(x) + ", " + std::to_string(y) + ", 0)\n" + more +
           "    uniform token[] xformOpOrder = [\"xformOp:translate\"" + moreOrder + "]\n";
}

// Five arrows: plain, turned, scaled unevenly, mirrored and tilted out of the image plane, and one
// hidden; a sheared one, which the instancer cannot place; a square of another asset.
std::string arrows(bool instanceable) {
    return std::string(kStage) + instance("A", "Arrow", instanceable, translate(-0.55, 0.55)) +
           instance("B", "Arrow", instanceable,
                    translate(0.55, 0.55, "    float xformOp:rotateZ = 120\n", ", \"xformOp:rotateZ\"")) +
           instance("C", "Arrow", instanceable,
                    translate(-0.55, -0.55, "    float3 xformOp:scale = (1.5, 0.6, 1)\n", ", \"xformOp:scale\"")) +
           instance("D", "Arrow", instanceable,
                    translate(0.55, -0.55, "    float3 xformOp:scale = (-1, 1, 1)\n    float3 xformOp:rotateXYZ = (0, 40, 20)\n",
                              ", \"xformOp:rotateXYZ\", \"xformOp:scale\"")) +
           instance("E", "Arrow", instanceable, translate(0, 0), "    token visibility = \"invisible\"\n") +
           instance("F", "Arrow", instanceable,
                    "    matrix4d xformOp:transform = ((1, 0, 0, 0), (0.6, 1, 0, 0), (0, 0, 1, 0), (0, -0.1, 0, 1))\n"
                    "    uniform token[] xformOpOrder = [\"xformOp:transform\"]\n") +
           instance("G", "Square", instanceable, translate(0, 0.75));
}

HostedStage open(const std::string& text) { return HostedStage(usda::Stage::openFromString(text, "arrows.usda")); }

std::map<std::string, int> typeCounts(const HostedStage& scene) {
    std::map<std::string, int> counts;
    for (const auto& [path, type] : scene.host->insertedPrims()) ++counts[type];
    return counts;
}

// A scene delegate in front of the host's that counts the plugin's pulls of each prim's points.
struct CountingPulls {
    const ObscuraSceneDelegate* host;
    ObscuraSceneDelegate table;
    std::map<std::string, int> pointPulls;

    explicit CountingPulls(HostedStage& scene) : host(&scene.host->sceneDelegate()), table(*host) {
        table.userData = this;
        table.getValue = [](void* user, const char* path, const char* attribute, double time, ObscuraValue* out) {
            auto* self = static_cast<CountingPulls*>(user);
            if (std::string(attribute) == "points") ++self->pointPulls[path];
            return self->host->getValue(self->host->userData, path, attribute, time, out);
        };
        table.getInterpolation = [](void* user, const char* path, const char* attribute, ObscuraInterpolation* out) {
            auto* self = static_cast<CountingPulls*>(user);
            return self->host->getInterpolation(self->host->userData, path, attribute, out);
        };
        table.sampleTransform = [](void* user, const char* path, double t0, double t1, uint32_t maxSamples,
                                   double* times, double* matrices, uint32_t* count) {
            auto* self = static_cast<CountingPulls*>(user);
            return self->host->sampleTransform(self->host->userData, path, t0, t1, maxSamples, times, matrices, count);
        };
        EXPECT_EQ(scene.api().setSceneDelegate(scene.delegate, &table), OBSCURA_OK);
    }
};

TEST(NativeInstancing, InstancesDrawAsTheSameSceneWithoutInstancing) {
    HostedStage instanced = open(arrows(true));
    HostedStage plain = open(arrows(false));
    const std::vector<float> a = instanced.renderAov("color", 4), b = plain.renderAov("color", 4);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    size_t covered = 0, differing = 0;
    double largest = 0.0;
    for (size_t i = 0; i < a.size(); i += 4) {
        if (b[i + 3] > 0.0f) ++covered;
        double difference = 0.0;
        for (size_t c = 0; c < 4; ++c) difference = std::max(difference, double(std::abs(a[i + c] - b[i + c])));
        if (difference > 1e-3) ++differing;
        largest = std::max(largest, difference);
    }
    EXPECT_GT(covered, 300u) << "the arrows cover part of the image";
    EXPECT_EQ(differing, 0u) << "largest difference " << largest;
}

TEST(NativeInstancing, OnePrototypeIsPulledOnceForAllItsInstances) {
    HostedStage instanced = open(arrows(true));
    // The arrows A..E share one prototype (its geometry under A); F shears, so it is served as
    // itself; G's square is a second prototype.
    auto counts = typeCounts(instanced);
    EXPECT_EQ(counts["instancer"], 2);
    EXPECT_EQ(counts["mesh"], 3);
    EXPECT_TRUE(instanced.host->insertedPrims().count("/A/Geom"));
    EXPECT_TRUE(instanced.host->insertedPrims().count("/F/Geom"));
    EXPECT_FALSE(instanced.host->insertedPrims().count("/B/Geom"));
    const harness::NativeInstancer& arrowInstancer = instanced.host->nativeInstancing().instancers().front();
    ObscuraValue indices{};
    const ObscuraSceneDelegate& table = instanced.host->sceneDelegate();
    ASSERT_EQ(table.getValue(table.userData, arrowInstancer.path.c_str(), "protoIndices", 0.0, &indices), OBSCURA_OK);
    EXPECT_EQ(indices.count, 5u);
    ObscuraValue hidden{};
    ASSERT_EQ(table.getValue(table.userData, arrowInstancer.path.c_str(), "invisibleIds", 0.0, &hidden), OBSCURA_OK);
    ASSERT_EQ(hidden.count, 1u);
    EXPECT_EQ(static_cast<const int32_t*>(hidden.data)[0], 4) << "E, the fifth instance";

    CountingPulls pulls(instanced);
    instanced.renderAov("color", 4);
    EXPECT_EQ(pulls.pointPulls, (std::map<std::string, int>{{"/A/Geom", 1}, {"/F/Geom", 1}, {"/G/Geom", 1}}));

    HostedStage plain = open(arrows(false));
    EXPECT_EQ(typeCounts(plain)["instancer"], 0);
    EXPECT_EQ(typeCounts(plain)["mesh"], 7);
    CountingPulls plainPulls(plain);
    plain.renderAov("color", 4);
    EXPECT_EQ(plainPulls.pointPulls.size(), 7u);
}

// The primId AOV names the prototype's geometry and instanceId the instance, which the host turns
// into the instance proxy's path, as usdview names a picked instance.
TEST(NativeInstancing, PickingNamesTheInstance) {
    HostedStage instanced = open(arrows(true));
    const std::vector<float> ids = instanced.renderAov("primId", 1), instances = instanced.renderAov("instanceId", 1);
    int32_t arrow = -1;
    ASSERT_EQ(instanced.api().getPrimId(instanced.delegate, "/A/Geom", &arrow), OBSCURA_OK);
    // The centre of the turned arrow B, at (0.55, 0.55): pixel (49, 15) of the 64-pixel view of
    // [-1.04775, 1.04775].
    const size_t pixel = size_t(15) * kWidth + 49;
    EXPECT_EQ(int32_t(ids[pixel]), arrow);
    EXPECT_EQ(int32_t(instances[pixel]), 1);
    EXPECT_EQ(instanced.host->instanceProxyPath("/A/Geom", 1), "/B/Geom");
    EXPECT_EQ(instanced.host->instanceProxyPath("/A/Geom", 5), "") << "five instances";
    EXPECT_EQ(instanced.host->instanceProxyPath("/F/Geom", 0), "") << "not instanced";
}

// Instances whose roots bind other materials draw with their own: they do not share a prototype
// (UsdImaging groups instances by the binding they hand down).
TEST(NativeInstancing, InstancesThatBindOtherMaterialsAreGroupedApart) {
    const std::string looks = R"(
def Scope "Looks"
{
    def Material "Red"
    {
        token outputs:surface.connect = </Looks/Red/Surface.outputs:surface>
        def Shader "Surface"
        {
            uniform token info:id = "UsdPreviewSurface"
            color3f inputs:diffuseColor = (0.8, 0.1, 0.1)
            token outputs:surface
        }
    }
}
)";
    const std::string bound = "    rel material:binding = </Looks/Red>\n";
    HostedStage scene = open(std::string(kStage) + looks + instance("A", "Arrow", true, translate(-0.5, 0)) +
                             instance("B", "Arrow", true, translate(0.5, 0), bound) +
                             instance("C", "Arrow", true, translate(0, 0.5), bound));
    const auto& instancers = scene.host->nativeInstancing().instancers();
    ASSERT_EQ(instancers.size(), 2u);
    EXPECT_EQ(instancers[0].instances.size(), 1u);
    EXPECT_EQ(instancers[1].instances.size(), 2u);
    const std::vector<float> albedo = scene.renderAlbedo();
    auto redAt = [&](int x, int y) { return albedo[(size_t(y) * kWidth + size_t(x)) * 3]; };
    // A at (-0.5, 0) keeps its displayColor; B at (0.5, 0) and C at (0, 0.5) are red.
    EXPECT_NEAR(redAt(17, 32), 0.8f, 0.02f);
    EXPECT_NEAR(albedo[(size_t(32) * kWidth + 17) * 3 + 1], 0.5f, 0.02f);
    EXPECT_NEAR(redAt(47, 32), 0.8f, 0.02f);
    EXPECT_NEAR(albedo[(size_t(32) * kWidth + 47) * 3 + 1], 0.1f, 0.02f);
    EXPECT_NEAR(albedo[(size_t(17) * kWidth + 32) * 3 + 1], 0.1f, 0.02f);
}

// Beneath an instance, the referencing layer's opinions are ignored (instance proxies compose only
// the instance's arcs): an override under the first instance does not reach the prototype, nor one
// under the second its instance. Without instancing the same overrides show.
TEST(NativeInstancing, OverridesBeneathInstancesDoNotShow) {
    const std::string blue = "    over \"Geom\"\n    {\n        color3f[] primvars:displayColor = [(0.1, 0.2, 0.9)]\n    }\n";
    auto albedoOf = [&](bool instanceable) {
        HostedStage scene = open(std::string(kStage) + instance("A", "Arrow", instanceable, translate(-0.5, 0), blue) +
                                 instance("B", "Arrow", instanceable, translate(0.5, 0), blue) +
                                 instance("C", "Arrow", instanceable, translate(0, 0.5)));
        EXPECT_EQ(scene.host->nativeInstancing().instancers().size(), instanceable ? 1u : 0u);
        return scene.renderAlbedo();
    };
    auto blueAt = [](const std::vector<float>& albedo, int x, int y) { return albedo[(size_t(y) * kWidth + size_t(x)) * 3 + 2]; };
    const std::vector<float> instanced = albedoOf(true), plain = albedoOf(false);
    // A at (-0.5, 0), B at (0.5, 0), C at (0, 0.5): the asset's orange everywhere when instanced.
    for (const auto& [x, y] : {std::pair{17, 32}, std::pair{47, 32}, std::pair{32, 17}})
        EXPECT_NEAR(blueAt(instanced, x, y), 0.2f, 0.02f) << x << "," << y;
    EXPECT_NEAR(blueAt(plain, 17, 32), 0.9f, 0.02f);
    EXPECT_NEAR(blueAt(plain, 47, 32), 0.9f, 0.02f);
    EXPECT_NEAR(blueAt(plain, 32, 17), 0.2f, 0.02f);
}

// A constant primvar on an instance root is inherited by the prototype's gprims that author none
// (USD's primvar inheritance), so each instance shows its root's colour: instances that hand down
// other values are grouped apart, those that hand down the same share. An arrow's own colour wins
// over its root's.
TEST(NativeInstancing, ConstantPrimvarsOfInstanceRootsColourTheirOwnInstances) {
    const std::string tile = R"(
class "Tile"
{
    def Mesh "Geom"
    {
        point3f[] points = [(-0.15, -0.15, 0), (0.15, -0.15, 0), (0.15, 0.15, 0), (-0.15, 0.15, 0)]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        uniform token subdivisionScheme = "none"
    }
}
)";
    auto colour = [](const char* rgb) { return "    color3f[] primvars:displayColor = [" + std::string(rgb) + "]\n"; };
    const std::string blue = colour("(0.1, 0.2, 0.9)"), red = colour("(0.9, 0.1, 0.1)");
    HostedStage scene = open(std::string(kStage) + tile + instance("A", "Tile", true, translate(-0.5, 0), blue) +
                             instance("B", "Tile", true, translate(0.5, 0), red) +
                             instance("C", "Tile", true, translate(0, 0.5), blue) +
                             instance("D", "Arrow", true, translate(0, -0.5), red));
    const auto& instancers = scene.host->nativeInstancing().instancers();
    ASSERT_EQ(instancers.size(), 3u) << "A and C, B, D";
    EXPECT_EQ(instancers[0].instances.size(), 2u);
    const std::vector<float> albedo = scene.renderAlbedo();
    auto rgbAt = [&](int x, int y) {
        const size_t i = (size_t(y) * kWidth + size_t(x)) * 3;
        return std::array<float, 3>{albedo[i], albedo[i + 1], albedo[i + 2]};
    };
    auto expectNear = [](const std::array<float, 3>& got, const std::array<float, 3>& want, const char* where) {
        for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 0.02f) << where << " channel " << c;
    };
    expectNear(rgbAt(17, 32), {0.1f, 0.2f, 0.9f}, "A");
    expectNear(rgbAt(47, 32), {0.9f, 0.1f, 0.1f}, "B");
    expectNear(rgbAt(32, 17), {0.1f, 0.2f, 0.9f}, "C");
    expectNear(rgbAt(32, 47), {0.8f, 0.5f, 0.2f}, "D, the arrow's own colour");
}

// Instances inside a prototype (windows of a building) are drawn with it: the delegate's instancer
// takes meshes as prototypes, not other instancers, so only the outermost instances are
// instanced. The image is the one drawn without instancing, every window in place.
TEST(NativeInstancing, NestedInstancesDrawWithTheirOuterPrototype) {
    auto buildings = [](bool instanceable) {
        const std::string flag = instanceable ? "true" : "false";
        auto window = [&](const char* name, double x) {
            return "    def Xform \"" + std::string(name) + "\" (instanceable = " + flag +
                   "\n        references = </Window>)\n    {\n        double3 xformOp:translate = (" + std::to_string(x) +
                   ", 0, 0.01)\n        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n    }\n";
        };
        return std::string(kStage) + R"(
class "Window"
{
    def Mesh "Pane"
    {
        point3f[] points = [(-0.06, -0.06, 0), (0.06, -0.06, 0), (0.06, 0.06, 0), (-0.06, 0.06, 0)]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        color3f[] primvars:displayColor = [(0.1, 0.2, 0.9)]
        uniform token subdivisionScheme = "none"
    }
}
class "Building"
{
    def Mesh "Wall"
    {
        point3f[] points = [(-0.3, -0.2, 0), (0.3, -0.2, 0), (0.3, 0.2, 0), (-0.3, 0.2, 0)]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        color3f[] primvars:displayColor = [(0.6, 0.6, 0.6)]
        uniform token subdivisionScheme = "none"
    }
)" + window("Left", -0.15) + window("Right", 0.15) + "}\n" +
               instance("North", "Building", instanceable, translate(0, 0.5)) +
               instance("South", "Building", instanceable,
                        translate(0, -0.5, "    float xformOp:rotateZ = 180\n", ", \"xformOp:rotateZ\"")) +
               instance("Sign", "Window", instanceable, translate(0.7, 0));
    };
    HostedStage instanced = open(buildings(true));
    HostedStage plain = open(buildings(false));
    // The buildings and the lone window are instanced; the first building's wall and windows are
    // its prototype's meshes, and the window's prototype is the sign's pane.
    auto counts = typeCounts(instanced);
    EXPECT_EQ(counts["instancer"], 2);
    EXPECT_EQ(counts["mesh"], 4);
    EXPECT_TRUE(instanced.host->insertedPrims().count("/North/Left/Pane"));
    EXPECT_FALSE(instanced.host->insertedPrims().count("/South/Left/Pane"));
    EXPECT_EQ(typeCounts(plain)["mesh"], 7);
    const std::vector<float> a = instanced.renderAlbedo(), b = plain.renderAlbedo();
    ASSERT_EQ(a.size(), b.size());
    size_t windows = 0, differing = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
        if (b[i + 2] > 0.8f) ++windows;
        if (std::abs(a[i] - b[i]) > 1e-3f || std::abs(a[i + 1] - b[i + 1]) > 1e-3f || std::abs(a[i + 2] - b[i + 2]) > 1e-3f)
            ++differing;
    }
    EXPECT_GT(windows, 5u * 8u) << "five windows of about 3.7 pixels square each";
    EXPECT_EQ(differing, 0u);
}

// The stage read again after an edit (the viewer's reload): moving one instance touches only its
// instancer, and the plugin then draws what it draws for the same edit without instancing (a
// second render, as a reload's, is compared with a second render: temporal accumulation differs
// from a first).
TEST(NativeInstancing, AnInstanceMovedByAnEditMovesWhenTheStageIsReadAgain) {
    auto renderEdited = [](bool instanceable, size_t expectedTouched) {
        HostedStage scene = open(arrows(instanceable));
        const std::vector<float> before = scene.renderAov("color", 4);
        EXPECT_EQ(scene.adopt(usda::Stage::openFromString(arrows(instanceable), "arrows.usda")), 0u)
            << "nothing changed";
        std::string edited = arrows(instanceable);
        const std::string placeOfB = "(0.550000, 0.550000, 0)";
        EXPECT_NE(edited.find(placeOfB), std::string::npos);
        edited.replace(edited.find(placeOfB), placeOfB.size(), "(0.200000, 0.300000, 0)");
        EXPECT_EQ(scene.adopt(usda::Stage::openFromString(edited, "arrows.usda")), expectedTouched);
        std::vector<float> after = scene.renderAov("color", 4);
        EXPECT_NE(after, before);
        return after;
    };
    const std::vector<float> instanced = renderEdited(true, 1), plain = renderEdited(false, 1);  // the instancer; B's mesh
    ASSERT_EQ(instanced.size(), plain.size());
    size_t differing = 0;
    for (size_t i = 0; i < instanced.size(); ++i)
        if (std::abs(instanced[i] - plain[i]) > 1e-3f) ++differing;
    EXPECT_EQ(differing, 0u);
}

}  // namespace
}  // namespace obscura::test
