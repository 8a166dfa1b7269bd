// The harness's flattening of UsdShade texture networks, end to end through UsdSceneHost and the
// plugin: tests/harness/data/textured.usda binds a Material whose UsdPreviewSurface reads its
// diffuseColor from a UsdUVTexture (an 8x8 PNG of four colour blocks, named relative to the
// layer), whose st comes from a UsdPrimvarReader_float2 with its varname on the material's
// interface, reading an indexed face-varying primvar "uv".
#include "harness/usd_scene_host.h"
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <variant>

namespace obscura::test {
namespace {

struct HostedStage {
    std::unique_ptr<usda::Stage> stage;
    std::optional<harness::LoadedPlugin> plugin;
    ObscuraDelegate delegate = nullptr;
    std::optional<harness::UsdSceneHost> host;
    std::vector<std::string> errors;

    explicit HostedStage(std::variant<std::unique_ptr<usda::Stage>, usda::Error> opened) {
        if (auto* error = std::get_if<usda::Error>(&opened)) throw std::runtime_error(error->str());
        stage = std::move(std::get<std::unique_ptr<usda::Stage>>(opened));
        auto loaded = harness::loadPlugin(builtPlugin());
        if (auto* error = std::get_if<std::string>(&loaded)) throw std::runtime_error(*error);
        plugin.emplace(std::move(std::get<harness::LoadedPlugin>(loaded)));
        ObscuraDelegateCreateInfo info{
            OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO, nullptr, sizeof(info), nullptr, 1, &HostedStage::log, this};
        if (api().createDelegate(&info, &delegate) != OBSCURA_OK) throw std::runtime_error(api().lastError(nullptr));
        host.emplace(*stage);
        if (api().setSceneDelegate(delegate, &host->sceneDelegate()) != OBSCURA_OK ||
            host->populate(api(), delegate) != OBSCURA_OK)
            throw std::runtime_error(api().lastError(delegate));
    }
    ~HostedStage() {
        if (delegate) api().destroyDelegate(delegate);
    }
    const ObscuraApiV1& api() const { return plugin->api(); }
    static void log(void* user, ObscuraLogLevel level, const char* message) {
        if (level == OBSCURA_LOG_ERROR) static_cast<HostedStage*>(user)->errors.push_back(message);
    }

    std::vector<float> renderAlbedo() {
        std::string buffer = host->addRenderBuffer(api(), delegate, "albedo", kWidth, kHeight);
        ObscuraAovBinding binding{"albedo", buffer.c_str()};
        std::string camera = host->defaultCamera();
        ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC,
                                   nullptr,
                                   sizeof(desc),
                                   camera.c_str(),
                                   {0, 0, 0, 0},
                                   0.0,
                                   1,
                                   &binding};
        EXPECT_EQ(api().render(delegate, &desc), OBSCURA_OK) << api().lastError(delegate);
        ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
        if (api().mapRenderBuffer(delegate, buffer.c_str(), &mapped) != OBSCURA_OK) return {};
        const auto* p = static_cast<const float*>(mapped.data);
        std::vector<float> out(p, p + size_t(mapped.width) * mapped.height * 3);
        api().unmapRenderBuffer(delegate, buffer.c_str());
        return out;
    }
    bool warned(const std::string& fragment) const {
        for (const auto& m : host->messages())
            if (m.text.find(fragment) != std::string::npos) return true;
        return false;
    }
};

void expectLinear(const std::vector<float>& albedo, int x, int y, std::array<int, 3> srgbCodes, const char* what) {
    for (size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(albedo.at((size_t(y) * kWidth + size_t(x)) * 3 + c), srgb8Exact(srgbCodes[c]), 0.004f)
            << what << " channel " << c;
}

TEST(TexturedUsda, ThePlaneShowsTheFourBlocks) {
    HostedStage scene(usda::Stage::open(OBSCURA_TEST_DATA_DIR "/textured.usda"));
    auto albedo = scene.renderAlbedo();
    ASSERT_EQ(albedo.size(), size_t(kWidth) * kHeight * 3);
    EXPECT_TRUE(scene.errors.empty()) << scene.errors.front();
    EXPECT_FALSE(scene.warned("not supported")) << "the texture network was not flattened";
    expectLinear(albedo, 16, 16, {200, 40, 40}, "top left");
    expectLinear(albedo, 48, 16, {40, 200, 40}, "top right");
    expectLinear(albedo, 16, 48, {40, 40, 200}, "bottom left");
    expectLinear(albedo, 48, 48, {220, 220, 60}, "bottom right");
}

TEST(TexturedUsda, TexturesOnOtherInputsStillWarn) {
    // specularColor is not textured by the delegate: its connection keeps the warning, and the
    // authored value is used.
    const std::string text = R"(#usda 1.0
def Material "M"
{
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:specularColor = (0.5, 0.5, 0.5)
        color3f inputs:specularColor.connect = </M/Texture.outputs:rgb>
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/checker.png@
        float3 outputs:rgb
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/inline.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    EXPECT_EQ(sd.getValue(sd.userData, "/M", "inputs:specularColor", 0.0, &value), OBSCURA_OK);
    EXPECT_TRUE(scene.warned("inputs:specularColor is connected"));
    EXPECT_EQ(sd.getValue(sd.userData, "/M", "obscura:specularColor:file", 0.0, &value), OBSCURA_ERROR_NOT_FOUND);
}

TEST(TexturedUsda, OcclusionTextureIsFlattenedLikeTheOtherInputs) {
    // inputs:occlusion (a constant, and a UsdUVTexture's r output) reaches the delegate as the
    // constant and obscura:occlusion:*, with no "connected" warning.
    const std::string text = R"(#usda 1.0
def Material "M"
{
    token outputs:surface.connect = </M/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        float inputs:occlusion = 0.75
        float inputs:occlusion.connect = </M/Texture.outputs:r>
        token outputs:surface
    }
    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/checker.png@
        token inputs:sourceColorSpace = "raw"
        float outputs:r
    }
}
)";
    HostedStage scene(usda::Stage::openFromString(text, OBSCURA_TEST_DATA_DIR "/inline.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "inputs:occlusion", 0.0, &value), OBSCURA_OK);
    EXPECT_FLOAT_EQ(static_cast<const float*>(value.data)[0], 0.75f);
    EXPECT_FALSE(scene.warned("inputs:occlusion is connected"));
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:occlusion:file", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::filesystem::path(static_cast<const char* const*>(value.data)[0]),
              std::filesystem::absolute(OBSCURA_TEST_DATA_DIR "/textures/checker.png").lexically_normal());
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:occlusion:channel", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::string(static_cast<const char* const*>(value.data)[0]), "r");
    ASSERT_EQ(sd.getValue(sd.userData, "/M", "obscura:occlusion:sourceColorSpace", 0.0, &value), OBSCURA_OK);
    EXPECT_EQ(std::string(static_cast<const char* const*>(value.data)[0]), "raw");
}

TEST(TexturedUsda, DomeTextureFileIsResolvedAgainstItsLayer) {
    // Hosts resolve asset paths: the delegate gets the file's absolute path.
    HostedStage scene(usda::Stage::open(OBSCURA_TEST_DATA_DIR "/dome.usda"));
    const ObscuraSceneDelegate& sd = scene.host->sceneDelegate();
    ObscuraValue value{};
    ASSERT_EQ(sd.getValue(sd.userData, "/Sky", "inputs:texture:file", 0.0, &value), OBSCURA_OK);
    ASSERT_EQ(value.type, OBSCURA_VALUE_TOKEN);
    std::string file = static_cast<const char* const*>(value.data)[0];
    EXPECT_EQ(std::filesystem::path(file),
              std::filesystem::absolute(OBSCURA_TEST_DATA_DIR "/textures/checker.png").lexically_normal());
    EXPECT_TRUE(std::filesystem::exists(file)) << file;
}

}  // namespace
}  // namespace obscura::test
