#include "tests/delegate/blur_scene.h"

#include <algorithm>

namespace obscura::test {

double pinholeUnitsPerPixel(double distance, int width) {
    const Lens pinhole;
    return distance * (pinhole.filmWidth / pinhole.focalLength) / width;
}

BlurScene::BlurScene(const Lens& lens, int w, int h) : CameraScene(lens, w, h) {
    setNumber("shadows", 0);
    setShutter(-0.5, 0.5);
}

image::Image BlurScene::render() {
    stillPasses_.clear();
    image::Image img = CameraScene::render();
    stillPasses_.push_back(passNames(host));
    for (int frame = 0; frame < 64 && !renderStats(host).converged; ++frame) {
        img = CameraScene::render();
        stillPasses_.push_back(passNames(host));
    }
    EXPECT_TRUE(renderStats(host).converged);
    return img;
}

bool BlurScene::ranUntilSettled(const std::string& pass) const {
    if (stillPasses_.size() < 2) return false;
    for (size_t frame = 0; frame + 1 < stillPasses_.size(); ++frame)
        if (std::find(stillPasses_[frame].begin(), stillPasses_[frame].end(), pass) == stillPasses_[frame].end())
            return false;
    return true;
}

bool BlurScene::ranInAnyFrame(const std::string& pass) const {
    for (const auto& names : stillPasses_)
        if (std::find(names.begin(), names.end(), pass) != names.end()) return true;
    return false;
}

void BlurScene::addSky() {
    host.addPrim("domeLight", "/Sky",
                 {{"inputs:intensity", HostValue::floatValue(1.0f)}, {"inputs:specular", HostValue::floatValue(0.0f)}});
}

void BlurScene::addMovingGlow(double sidePixels, double distance, double travelPixels, float radiance) {
    addMaterial(host, "/GlowLook", {0, 0, 0}, 1.0f, 0.0f, {radiance, radiance, radiance});
    addPlane(host, "/Glow", "/GlowLook", 0.5 * sidePixels * unitsPerPixel(distance), translation(0, 0, -distance));
    double travel = travelPixels * unitsPerPixel(distance);
    host.setTransformMotion("/Glow", -0.5, translation(-0.5 * travel, 0, -distance), 0.5,
                            translation(0.5 * travel, 0, -distance));
}

void BlurScene::addDeformingGlow(double sidePixels, double distance, double travelPixels) {
    addMovingGlow(sidePixels, distance, 0.0);
    host.setTransform("/Glow", translation(0, 0, -distance));
    float h = float(0.5 * sidePixels * unitsPerPixel(distance)), t = float(0.5 * travelPixels * unitsPerPixel(distance));
    auto square = [h](float dx) {
        return HostValue::points({{dx - h, -h, 0}, {dx + h, -h, 0}, {dx + h, h, 0}, {dx - h, h, 0}});
    };
    host.setTimeSamples("/Glow", "points", {{-0.5, square(-t)}, {0.5, square(t)}});
}

image::Image BlurScene::sharp() {
    setNumber("motionBlur", 0);
    image::Image img = render();
    setNumber("motionBlur", 1);
    return img;
}

float luminance(const image::Image& img, int x, int y) {
    return 0.2126f * img.at(x, y, 0) + 0.7152f * img.at(x, y, 1) + 0.0722f * img.at(x, y, 2);
}

double sweptCoverage(int x, double centre, double side, double travel) {
    constexpr int kSteps = 4096;
    double covered = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        double at = centre + travel * ((i + 0.5) / kSteps - 0.5);
        covered += std::max(0.0, std::min(x + 1.0, at + 0.5 * side) - std::max(double(x), at - 0.5 * side));
    }
    return covered / kSteps;
}

std::vector<double> rowProfile(const image::Image& img, int y0, int y1) {
    std::vector<double> p(size_t(img.width), 0.0);
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < img.width; ++x) p[size_t(x)] += luminance(img, x, y) / (y1 - y0);
    return p;
}

Streak measureStreak(const std::vector<double>& p, int plateauWidth) {
    Streak s{0, 0, 0};
    int first = -1, last = -1;
    for (size_t x = 0; x < p.size(); ++x) {
        s.integral += p[x];
        if (p[x] > 1.0 / 256.0) {
            if (first < 0) first = int(x);
            last = int(x);
        }
    }
    s.length = first < 0 ? 0 : last - first + 1;
    int centre = int(p.size()) / 2;
    for (int x = centre - plateauWidth / 2; x < centre + plateauWidth / 2; ++x) s.plateau += p[size_t(x)] / plateauWidth;
    return s;
}

}  // namespace obscura::test
