#include "harness/aov_output.h"

#include "harness/image/exr_writer.h"
#include "harness/image/png_io.h"

namespace obscura::harness {

std::string writeExrAovs(const std::string& path, const std::vector<MappedAov>& aovs,
                         const schema::CameraDepth& camera) {
    std::vector<image::ExrLayer> layers;
    std::vector<std::vector<float>> converted;  // keeps converted depth alive until written
    converted.reserve(aovs.size());
    int width = 0, height = 0;
    for (const auto& m : aovs) {
        const auto& b = m.buffer;
        width = int(b.width);
        height = int(b.height);
        using PT = image::ExrLayer::PixelType;
        if (m.aov == "color") {
            layers.push_back({"", {"R", "G", "B", "A"}, PT::Float, b.data, b.rowStride});
        } else if (m.aov == "depth") {
            converted.emplace_back(size_t(b.width) * b.height);
            const auto* src = static_cast<const float*>(b.data);
            for (size_t i = 0; i < converted.back().size(); ++i)
                converted.back()[i] = float(schema::viewDistance(src[i], camera));
            layers.push_back({"depth", {"Z"}, PT::Float, converted.back().data(), size_t(b.width) * sizeof(float)});
        } else if (m.aov == "normal") {
            layers.push_back({"normal", {"X", "Y", "Z"}, PT::Float, b.data, b.rowStride});
        } else if (m.aov == "albedo") {
            layers.push_back({"albedo", {"R", "G", "B"}, PT::Half, b.data, b.rowStride});
        } else if (m.aov == "motion") {
            layers.push_back({"motion", {"X", "Y", "Z"}, PT::Float, b.data, b.rowStride});
        } else if (m.aov == "primId" || m.aov == "instanceId") {
            layers.push_back({m.aov, {"id"}, PT::Uint, b.data, b.rowStride});
        }
    }
    auto status = image::writeExr(path, width, height, layers);
    return image::isError(status) ? image::errorOf(status) : std::string();
}

std::string writePngDisplay(const std::string& path, const ObscuraMappedBuffer& display) {
    auto status = image::writePng(path, int(display.width), int(display.height), image::PngFormat::Rgba,
                                  static_cast<const uint8_t*>(display.data), display.rowStride);
    return image::isError(status) ? image::errorOf(status) : std::string();
}

}  // namespace obscura::harness
