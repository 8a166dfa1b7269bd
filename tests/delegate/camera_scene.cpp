#include "tests/delegate/camera_scene.h"

#include "harness/image/png_io.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace obscura::test {

CameraScene::CameraScene(const Lens& lens, int w, int h) : width(w), height(h) {
    // Looking down -Z from the origin; a square film gate, so the image is square too.
    host.addPrim("camera", "/Camera",
                 {{"focalLength", HostValue::floatValue(lens.focalLength)},
                  {"horizontalAperture", HostValue::floatValue(lens.filmWidth)},
                  {"verticalAperture", HostValue::floatValue(lens.filmWidth * float(h) / float(w))},
                  {"clippingRange", HostValue::float2(0.5f, 1000.0f)},
                  {"fStop", HostValue::floatValue(lens.fStop)},
                  {"focusDistance", HostValue::floatValue(lens.focusDistance)},
                  {"obscura:apertureBlades", HostValue::intValue(lens.blades)},
                  {"obscura:apertureRotation", HostValue::floatValue(lens.rotationDegrees)}});
    host.addRenderBuffer("/Buffers/color", "float32Vec4", w, h);
    setNumber("ssao", 0);
}

void CameraScene::setNumber(const char* name, double value) { test::setNumber(host, name, value); }

void CameraScene::setShutter(double open, double close) {
    host.set("/Camera", "shutter:open", HostValue::doubleValue(open));
    host.set("/Camera", "shutter:close", HostValue::doubleValue(close));
    host.api().markDirty(host.delegate(), "/Camera", OBSCURA_DIRTY_PARAMS);
}

image::Image CameraScene::render(double time) {
    EXPECT_EQ(host.render("/Camera", {{"color", "/Buffers/color"}}, time), OBSCURA_OK) << host.lastError();
    EXPECT_TRUE(host.loggedErrors().empty()) << host.loggedErrors().front();
    std::vector<float> rgba = host.readFloats("/Buffers/color");
    image::Image img = image::Image::make(width, height, {"R", "G", "B"});
    for (size_t p = 0; p < size_t(width) * height; ++p)
        for (int c = 0; c < 3; ++c) img.pixels[p * 3 + c] = rgba[p * 4 + c];
    return img;
}

image::Image CameraScene::renderReference(int subFrames, double time) {
    setNumber("reference", subFrames);
    image::Image img = render(time);
    setNumber("reference", 0);
    return img;
}

void CameraScene::addChequerCard(Chequer kind, const std::string& path, std::array<double, 3> centre,
                                 double cellSize, int cellsX, int cellsY, std::array<float, 3> light,
                                 std::array<float, 3> dark) {
    if (kind == Chequer::Geometry) return test::addChequerCard(host, path, centre, cellSize, cellsX, cellsY, light, dark);
    if (files_.empty()) {
        files_ = std::filesystem::temp_directory_path() /
                 ("obscura_chequers_" + std::to_string(getpid()) + "_" + std::to_string(reinterpret_cast<uintptr_t>(this)));
        std::filesystem::create_directories(files_);
    }
    constexpr int kTexelsPerCell = 16;
    const int w = cellsX * kTexelsPerCell, h = cellsY * kTexelsPerCell;
    std::vector<uint8_t> bytes;
    for (int y = 0; y < h; ++y)  // row 0 at the top: the card's cell row cellsY - 1
        for (int x = 0; x < w; ++x) {
            const int i = x / kTexelsPerCell, j = cellsY - 1 - y / kTexelsPerCell;
            for (float c : (i + j) % 2 ? dark : light)
                bytes.push_back(uint8_t(std::lround(255.0f * srgbEncode(std::clamp(c, 0.0f, 1.0f)))));
        }
    const std::string file = (files_ / (path.substr(path.rfind('/') + 1) + ".png")).string();
    auto written = image::writePng(file, w, h, image::PngFormat::Rgb, bytes.data(), size_t(w) * 3);
    EXPECT_FALSE(image::isError(written)) << image::errorOf(written);
    const std::string look = path + "Look";
    host.addPrim("material", look,
                 {{"obscura:diffuseColor:file", HostValue::token(file)},
                  {"obscura:diffuseColor:wrapS", HostValue::token("clamp")},
                  {"obscura:diffuseColor:wrapT", HostValue::token("clamp")}});
    const float hx = float(0.5 * cellSize * cellsX), hy = float(0.5 * cellSize * cellsY);
    host.addPrim("mesh", path,
                 {{"points", HostValue::points({{-hx, -hy, 0}, {hx, -hy, 0}, {hx, hy, 0}, {-hx, hy, 0}})},
                  {"faceVertexCounts", HostValue::intArray({4})},
                  {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                  {"subdivisionScheme", HostValue::token("none")},
                  {"primvars:st", HostValue::float2Array({{0, 0}, {1, 0}, {1, 1}, {0, 1}})},
                  {"material:binding", HostValue::path(look)}},
                 translation(centre[0], centre[1], centre[2]));
}

CameraScene::~CameraScene() {
    if (!files_.empty()) std::filesystem::remove_all(files_);
}

void addChequerCard(TestHost& host, const std::string& path, std::array<double, 3> centre, double cellSize,
                    int cellsX, int cellsY, std::array<float, 3> light, std::array<float, 3> dark) {
    std::vector<std::array<float, 3>> points, colours;
    std::vector<int32_t> counts, indices;
    for (int j = 0; j <= cellsY; ++j)
        for (int i = 0; i <= cellsX; ++i)
            points.push_back({float(cellSize * (i - 0.5 * cellsX)), float(cellSize * (j - 0.5 * cellsY)), 0.0f});
    for (int j = 0; j < cellsY; ++j)
        for (int i = 0; i < cellsX; ++i) {
            int a = j * (cellsX + 1) + i;
            counts.push_back(4);
            indices.insert(indices.end(), {a, a + 1, a + cellsX + 2, a + cellsX + 1});
            colours.push_back((i + j) % 2 ? dark : light);
        }
    host.addPrim("mesh", path,
                 {{"points", HostValue::points(points)},
                  {"faceVertexCounts", HostValue::intArray(counts)},
                  {"faceVertexIndices", HostValue::intArray(indices)},
                  {"subdivisionScheme", HostValue::token("none")},
                  {"primvars:displayColor", HostValue::points(colours)}},
                 translation(centre[0], centre[1], centre[2]));
    host.setInterpolation(path, "primvars:displayColor", OBSCURA_INTERPOLATION_UNIFORM);
}

image::CompareMetrics metrics(const image::Image& a, const image::Image& b) {
    auto result = image::compare(a, b);
    EXPECT_FALSE(image::isError(result));
    return image::isError(result) ? image::CompareMetrics{} : std::get<image::CompareMetrics>(result);
}

double mappedPsnr(const image::Image& a, const image::Image& b) {
    auto mapped = [](const image::Image& img) {
        image::Image m = image::Image::make(img.width, img.height, {"R", "G", "B"});
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                for (int c = 0; c < 3; ++c) m.at(x, y, c) = img.at(x, y, c) / (1.0f + img.at(x, y, c));
        return m;
    };
    return metrics(mapped(a), mapped(b)).psnr;
}

image::Image crop(const image::Image& img, int x0, int y0, int x1, int y1) {
    image::Image c = image::Image::make(x1 - x0, y1 - y0, img.channels);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int k = 0; k < int(img.channelCount()); ++k) c.at(x - x0, y - y0, k) = img.at(x, y, k);
    return c;
}

std::vector<std::string> passNames(TestHost& host) {
    uint32_t count = 0;
    host.api().getPassTimings(host.delegate(), nullptr, &count);
    std::vector<ObscuraPassTiming> timings(count);
    for (auto& t : timings) t.sType = OBSCURA_STRUCTURE_TYPE_PASS_TIMING, t.structSize = sizeof(t);
    host.api().getPassTimings(host.delegate(), timings.data(), &count);
    std::vector<std::string> names;
    for (const auto& t : timings) names.push_back(t.pass);
    return names;
}

bool ranPass(TestHost& host, const std::string& name) {
    auto names = passNames(host);
    return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace obscura::test
