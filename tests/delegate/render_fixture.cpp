#include "tests/delegate/render_fixture.h"

#include <algorithm>

namespace obscura::test {

Matrix lightPointingAlong(std::array<double, 3> d) {
    double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (auto& c : d) c /= len;
    // Local Z axis = -direction; build an orthonormal basis around it (rows are the images of
    // the local axes in the row-vector convention).
    std::array<double, 3> z = {-d[0], -d[1], -d[2]};
    std::array<double, 3> up = std::fabs(z[1]) < 0.9 ? std::array<double, 3>{0, 1, 0} : std::array<double, 3>{1, 0, 0};
    std::array<double, 3> x = {up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]};
    double xl = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (auto& c : x) c /= xl;
    std::array<double, 3> y = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
    return {x[0], x[1], x[2], 0, y[0], y[1], y[2], 0, z[0], z[1], z[2], 0, 0, 0, 0, 1};
}

ObscuraRenderStats renderStats(TestHost& host) {
    ObscuraRenderStats s{};
    s.structSize = sizeof(s);
    host.api().getRenderStats(host.delegate(), &s);
    return s;
}

void setNumber(TestHost& host, const char* name, double value) {
    ObscuraValue v{OBSCURA_VALUE_DOUBLE, 0, 1, &value};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), name, &v), OBSCURA_OK) << host.lastError();
}

void setToken(TestHost& host, const char* name, const std::string& value) {
    const char* text = value.c_str();
    ObscuraValue v{OBSCURA_VALUE_TOKEN, 0, 1, &text};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), name, &v), OBSCURA_OK) << host.lastError();
}

void setBool(TestHost& host, const char* name, bool on) {
    int32_t flag = on ? 1 : 0;
    ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &flag};
    ASSERT_EQ(host.api().setRenderSetting(host.delegate(), name, &v), OBSCURA_OK) << host.lastError();
}

void addPlane(TestHost& host, const std::string& path, const std::string& material, double half, Matrix transform) {
    float h = float(half);
    std::map<std::string, HostValue> values = {
        {"points", HostValue::points({{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}})},
        {"faceVertexCounts", HostValue::intArray({4})},
        {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
        {"subdivisionScheme", HostValue::token("none")},
    };
    if (!material.empty()) values["material:binding"] = HostValue::path(material);
    host.addPrim("mesh", path, values, transform);
}

void addMaterial(TestHost& host, const std::string& path, std::array<float, 3> diffuse, float roughness,
                 float metallic, std::array<float, 3> emissive) {
    host.addPrim("material", path,
                 {{"inputs:diffuseColor", HostValue::float3(diffuse[0], diffuse[1], diffuse[2])},
                  {"inputs:roughness", HostValue::floatValue(roughness)},
                  {"inputs:metallic", HostValue::floatValue(metallic)},
                  {"inputs:emissiveColor", HostValue::float3(emissive[0], emissive[1], emissive[2])}});
}

double diskIrradiance(double radiance, double r, double h, double rho) {
    double z = h * h + rho * rho + r * r;
    return kPi * radiance * 0.5 * (1 - (h * h + rho * rho - r * r) / std::sqrt(z * z - 4 * r * r * rho * rho));
}

float smallFloatStep(float v, int mantissaBits) {
    if (v <= 0.0f) return 0.0f;
    int exponent = 0;
    std::frexp(v, &exponent);  // v = m * 2^exponent, m in [0.5, 1)
    return std::ldexp(1.0f, exponent - 1 - mantissaBits);
}

float srgbDecode(double c) { return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4)); }

float srgbEncode(double v) { return float(v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055); }

float srgb8Exact(int code) { return srgbDecode(code / 255.0); }

std::array<double, 2> environmentBrdf(double roughness, double NdotV) {
    const double c0[4] = {-1.0, -0.0275, -0.572, 0.022}, c1[4] = {1.0, 0.0425, 1.04, -0.04};
    double r[4];
    for (int i = 0; i < 4; ++i) r[i] = roughness * c0[i] + c1[i];
    double a004 = std::min(r[0] * r[0], std::exp2(-9.28 * NdotV)) * r[0] + r[1];
    return {-1.04 * a004 + r[2], 1.04 * a004 + r[3]};
}

std::array<double, 3> planePointAtPixel(int x, int y, double distance, double tanHalfFov, int size) {
    double ndcX = (x + 0.5) / size * 2.0 - 1.0;
    double ndcY = 1.0 - (y + 0.5) / size * 2.0;  // row 0 is the top of the image
    return {ndcX * tanHalfFov * distance, ndcY * tanHalfFov * distance, 0.0};
}

const float kLitPlaneAlbedo = srgb8Exact(188);

LitPlaneScene::LitPlaneScene() {
    host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
    addMaterial(host, "/Looks/Grey", {kLitPlaneAlbedo, kLitPlaneAlbedo, kLitPlaneAlbedo});
    addPlane(host, "/Plane", "/Looks/Grey");
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
}

void addLitPlaneViewAndSun(TestHost& host, double irradiance) {
    host.addCamera("/Camera", translation(0, 0, kLitPlaneCameraDistance), kLitPlaneFocalLength, kLitPlaneAperture);
    host.addPrim("distantLight", "/Sun",
                 {{"inputs:intensity", HostValue::floatValue(float(irradiance))},
                  {"inputs:normalize", HostValue::boolean(true)},
                  {"inputs:specular", HostValue::floatValue(0.0f)}},
                 lightPointingAlong({0.0, 0.0, -1.0}));
    host.addRenderBuffer("/Buffers/color", "float32Vec4", kWidth, kHeight);
}

std::vector<float> LitPlaneScene::renderColor() {
    EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}), OBSCURA_OK) << host.lastError();
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    return host.readFloats("/Buffers/color");
}

void expectRadiance(const std::vector<float>& color, int x, int y, std::array<double, 3> expected) {
    const float* p = &color[(size_t(y) * kWidth + x) * 4];
    const int mantissa[3] = {6, 6, 5};
    for (int c = 0; c < 3; ++c) {
        double e = expected[c];
        EXPECT_NEAR(p[c], e, 0.01 * e + smallFloatStep(float(e), mantissa[c]))
            << "pixel (" << x << ", " << y << ") channel " << c;
    }
    EXPECT_EQ(p[3], 1.0f);
}

void addBox(TestHost& host, const std::string& path, std::array<double, 3> lo, std::array<double, 3> hi,
            const std::string& material) {
    float x0 = float(lo[0]), y0 = float(lo[1]), z0 = float(lo[2]);
    float x1 = float(hi[0]), y1 = float(hi[1]), z1 = float(hi[2]);
    host.addPrim("mesh", path,
                 {{"points", HostValue::points({{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                                                {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}})},
                  {"faceVertexCounts", HostValue::intArray({4, 4, 4, 4, 4, 4})},
                  {"faceVertexIndices", HostValue::intArray({0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7,
                                                             6, 3, 0, 4, 7})},
                  {"subdivisionScheme", HostValue::token("none")},
                  {"material:binding", HostValue::path(material)}});
}

Matrix lookingAlongY(std::array<double, 3> eye, double pitchDegrees) {
    double p = pitchDegrees * kPi / 180.0;
    return {1, 0, 0, 0, 0, std::sin(p), std::cos(p), 0, 0, -std::cos(p), std::sin(p), 0, eye[0], eye[1], eye[2], 1};
}

Matrix turnedAndMoved(double degrees, double x, double y, double z) {
    double a = degrees * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    return {c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, x, y, z, 1};
}

image::Image rgbImage(const std::vector<float>& rgba, int width, int height) {
    image::Image out = image::Image::make(width, height, {"R", "G", "B"});
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgba[(size_t(y) * width + x) * 4 + c];
    return out;
}

image::Image boxDownsample(const std::vector<float>& rgba, int width, int height, int factor,
                           float (*transfer)(float)) {
    image::Image out = image::Image::make(width / factor, height / factor, {"R", "G", "B"});
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = rgba[(size_t(y) * width + x) * 4 + c];
                out.at(x / factor, y / factor, c) += (transfer ? transfer(v) : v) / float(factor * factor);
            }
    return out;
}

image::CompareMetrics compareImages(const image::Image& a, const image::Image& b) {
    auto result = image::compare(a, b);
    EXPECT_FALSE(image::isError(result));
    return image::isError(result) ? image::CompareMetrics{} : std::get<image::CompareMetrics>(result);
}

}  // namespace obscura::test
