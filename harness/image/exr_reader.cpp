#include "harness/image/exr_reader.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string_view>

namespace obscura::image {
namespace {

// 4 GiB of float samples: far beyond any frame the harness renders.
constexpr int64_t kMaxSamples = int64_t{1} << 30;

struct FileChannel {
    std::string name;
    Imf::PixelType type;
};

// R, G, B, A before everything else, so images read the way people list them.
std::vector<FileChannel> orderedChannels(const Imf::ChannelList& list) {
    static constexpr std::array<std::string_view, 4> kColour = {"R", "G", "B", "A"};
    std::vector<FileChannel> ordered;
    for (std::string_view name : kColour) {
        if (const Imf::Channel* c = list.findChannel(std::string(name))) {
            ordered.push_back({std::string(name), c->type});
        }
    }
    for (auto it = list.begin(); it != list.end(); ++it) {
        if (std::find(kColour.begin(), kColour.end(), it.name()) == kColour.end()) {
            ordered.push_back({it.name(), it.channel().type});
        }
    }
    return ordered;
}

}  // namespace

Result<Image> readExr(const std::string& path) {
    // OpenEXR's own message for a missing file is generic; say plainly what is wrong.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return path + ": no such file";

    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i dw = header.dataWindow();
        // 64-bit arithmetic: a corrupt header must not overflow into a small allocation.
        const int64_t width = int64_t{dw.max.x} - dw.min.x + 1;
        const int64_t height = int64_t{dw.max.y} - dw.min.y + 1;
        if (width <= 0 || height <= 0) return path + ": empty data window";

        const std::vector<FileChannel> channels = orderedChannels(header.channels());
        if (channels.empty()) return path + ": no channels";
        // A corrupt header can claim any size; refuse before allocating for it.
        if (width > kMaxSamples / height / static_cast<int64_t>(channels.size())) {
            return path + ": data window too large";
        }
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1) {
                return path + ": channel '" + it.name() + "' is subsampled (not supported)";
            }
        }

        std::vector<std::string> names;
        for (const FileChannel& c : channels) names.push_back(c.name);
        Image image = Image::make(static_cast<int>(width), static_cast<int>(height), names);

        // Float channels go straight into the interleaved pixels; UINT channels into their own
        // buffers, converted afterwards (OpenEXR would convert UINT -> float by value, not by
        // int32 bit pattern).
        const size_t pixelCount = static_cast<size_t>(width) * static_cast<size_t>(height);
        const size_t xStride = channels.size() * sizeof(float);
        std::vector<std::vector<uint32_t>> uintBuffers(channels.size());
        Imf::FrameBuffer frameBuffer;
        for (size_t c = 0; c < channels.size(); ++c) {
            if (channels[c].type == Imf::UINT) {
                uintBuffers[c].resize(pixelCount);
                frameBuffer.insert(channels[c].name,
                                   Imf::Slice::Make(Imf::UINT, uintBuffers[c].data(), dw,
                                                    sizeof(uint32_t)));
            } else {
                frameBuffer.insert(channels[c].name,
                                   Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, dw,
                                                    xStride, xStride * static_cast<size_t>(width)));
            }
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(dw.min.y, dw.max.y);

        for (size_t c = 0; c < channels.size(); ++c) {
            if (uintBuffers[c].empty()) continue;
            for (size_t i = 0; i < pixelCount; ++i) {
                image.pixels[i * channels.size() + c] =
                    static_cast<float>(std::bit_cast<int32_t>(uintBuffers[c][i]));
            }
        }
        return image;
    } catch (const std::exception& e) {
        return path + ": cannot read EXR: " + e.what();
    }
}

}  // namespace obscura::image
