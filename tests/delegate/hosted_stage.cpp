#include "tests/delegate/hosted_stage.h"

#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace obscura::test {

std::string usdaCamera(const std::string& attributes) {
    return "def Camera \"Camera\"\n{\n"
           "    float focalLength = 50\n"
           "    float horizontalAperture = 20.955\n"
           "    float verticalAperture = 20.955\n"
           "    float2 clippingRange = (0.1, 100)\n" +
           attributes +
           "    double3 xformOp:translate = (0, 0, 5)\n"
           "    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n";
}

HostedStage::HostedStage(std::variant<std::unique_ptr<usda::Stage>, usda::Error> opened) {
    if (auto* error = std::get_if<usda::Error>(&opened)) throw std::runtime_error(error->str());
    stage = std::move(std::get<std::unique_ptr<usda::Stage>>(opened));
    auto loaded = harness::loadPlugin(builtPlugin());
    if (auto* error = std::get_if<std::string>(&loaded)) throw std::runtime_error(*error);
    plugin.emplace(std::move(std::get<harness::LoadedPlugin>(loaded)));
    ObscuraDelegateCreateInfo info{
        OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO, nullptr, sizeof(info), nullptr, 1, &HostedStage::log, this};
    if (api().createDelegate(&info, &delegate) != OBSCURA_OK) throw std::runtime_error(api().lastError(nullptr));
    host = std::make_unique<harness::UsdSceneHost>(*stage);
    if (api().setSceneDelegate(delegate, &host->sceneDelegate()) != OBSCURA_OK ||
        host->populate(api(), delegate) != OBSCURA_OK)
        throw std::runtime_error(api().lastError(delegate));
}

HostedStage::~HostedStage() {
    if (delegate) EXPECT_EQ(api().destroyDelegate(delegate), OBSCURA_OK) << api().lastError(delegate);
    expected_.check(errors, "the plugin");
}

size_t HostedStage::adopt(std::variant<std::unique_ptr<usda::Stage>, usda::Error> edited, double time) {
    if (auto* error = std::get_if<usda::Error>(&edited)) throw std::runtime_error(error->str());
    auto editedStage = std::move(std::get<std::unique_ptr<usda::Stage>>(edited));
    auto editedHost = std::make_unique<harness::UsdSceneHost>(*editedStage);
    size_t touched = 0;
    EXPECT_EQ(editedHost->adoptChanges(*host, api(), delegate, time, touched), OBSCURA_OK) << api().lastError(delegate);
    EXPECT_EQ(api().setSceneDelegate(delegate, &editedHost->sceneDelegate()), OBSCURA_OK);
    host = std::move(editedHost);
    stage = std::move(editedStage);
    return touched;
}

void HostedStage::log(void* user, ObscuraLogLevel level, const char* message) {
    if (level == OBSCURA_LOG_ERROR) static_cast<HostedStage*>(user)->errors.push_back(message);
    if (level == OBSCURA_LOG_WARNING) static_cast<HostedStage*>(user)->warnings.push_back(message);
}

std::vector<float> HostedStage::renderAov(const std::string& aov, size_t channels, double time) {
    std::string buffer = host->addRenderBuffer(api(), delegate, aov, kWidth, kHeight);
    ObscuraAovBinding binding{aov.c_str(), buffer.c_str()};
    std::string camera = host->defaultCamera();
    ObscuraRenderPassDesc desc{OBSCURA_STRUCTURE_TYPE_RENDER_PASS_DESC,
                               nullptr,
                               sizeof(desc),
                               camera.c_str(),
                               {0, 0, 0, 0},
                               time,
                               1,
                               &binding};
    lastStatus = api().render(delegate, &desc);
    // Bad prim data is skipped and reported; the rest renders.
    EXPECT_TRUE(lastStatus == OBSCURA_OK || lastStatus == OBSCURA_ERROR_BAD_PRIM_DATA) << api().lastError(delegate);
    ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
    if (api().mapRenderBuffer(delegate, buffer.c_str(), &mapped) != OBSCURA_OK) return {};
    size_t count = size_t(mapped.width) * mapped.height * channels;
    std::vector<float> out(count);
    if (aov == "primId" || aov == "instanceId") {
        const auto* p = static_cast<const int32_t*>(mapped.data);
        for (size_t i = 0; i < count; ++i) out[i] = float(p[i]);
    } else {
        const auto* p = static_cast<const float*>(mapped.data);
        out.assign(p, p + count);
    }
    api().unmapRenderBuffer(delegate, buffer.c_str());
    return out;
}

void HostedStage::setToken(const std::string& name, const std::string& token) {
    const char* text = token.c_str();
    ObscuraValue value{OBSCURA_VALUE_TOKEN, 0, 1, &text};
    EXPECT_EQ(api().setRenderSetting(delegate, name.c_str(), &value), OBSCURA_OK) << api().lastError(delegate);
}

void HostedStage::setBool(const std::string& name, bool on) {
    int32_t flag = on ? 1 : 0;
    ObscuraValue value{OBSCURA_VALUE_BOOL, 0, 1, &flag};
    EXPECT_EQ(api().setRenderSetting(delegate, name.c_str(), &value), OBSCURA_OK) << api().lastError(delegate);
}

size_t HostedStage::messagesWith(const std::string& fragment) const {
    size_t count = 0;
    for (const auto& m : host->messages()) count += m.text.find(fragment) != std::string::npos;
    return count;
}

std::vector<float> HostedStage::floats(const std::string& path, const std::string& attribute) const {
    const ObscuraSceneDelegate& sd = host->sceneDelegate();
    ObscuraValue value{};
    if (sd.getValue(sd.userData, path.c_str(), attribute.c_str(), 0.0, &value) != OBSCURA_OK) {
        ADD_FAILURE() << "no value for " << path << " " << attribute;
        return {};
    }
    const size_t width = value.type == OBSCURA_VALUE_FLOAT4   ? 4
                         : value.type == OBSCURA_VALUE_FLOAT3 ? 3
                         : value.type == OBSCURA_VALUE_FLOAT2 ? 2
                                                              : 1;
    const auto* data = static_cast<const float*>(value.data);
    return std::vector<float>(data, data + width * value.count);
}

std::string HostedStage::token(const std::string& path, const std::string& attribute) const {
    const ObscuraSceneDelegate& sd = host->sceneDelegate();
    ObscuraValue value{};
    if (sd.getValue(sd.userData, path.c_str(), attribute.c_str(), 0.0, &value) != OBSCURA_OK || value.count != 1) {
        ADD_FAILURE() << "no token for " << path << " " << attribute;
        return {};
    }
    return static_cast<const char* const*>(value.data)[0];
}

bool HostedStage::served(const std::string& path, const std::string& attribute) const {
    const ObscuraSceneDelegate& sd = host->sceneDelegate();
    ObscuraValue value{};
    return sd.getValue(sd.userData, path.c_str(), attribute.c_str(), 0.0, &value) == OBSCURA_OK;
}

}  // namespace obscura::test
