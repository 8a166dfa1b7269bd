#include "harness/image/exr_writer.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfThreading.h>

#include <exception>
#include <list>
#include <mutex>
#include <set>
#include <thread>

namespace obscura::image {
namespace {

Imf::Compression toImf(ExrCompression c) {
    switch (c) {
        case ExrCompression::None: return Imf::NO_COMPRESSION;
        case ExrCompression::Zip: return Imf::ZIP_COMPRESSION;
        case ExrCompression::Zips: return Imf::ZIPS_COMPRESSION;
        case ExrCompression::Piz: return Imf::PIZ_COMPRESSION;
        case ExrCompression::Rle: return Imf::RLE_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

Imf::PixelType fileType(ExrLayer::PixelType t) {
    switch (t) {
        case ExrLayer::PixelType::Half: return Imf::HALF;
        case ExrLayer::PixelType::Float: return Imf::FLOAT;
        case ExrLayer::PixelType::Uint: return Imf::UINT;
    }
    return Imf::FLOAT;
}

// OpenEXR's output files do not convert pixel types, so Half layers, given as float, are rounded
// into a half buffer first (same layout, rows packed).
std::vector<half> toHalf(const ExrLayer& layer, int width, int height) {
    const size_t rowValues = static_cast<size_t>(width) * layer.channelNames.size();
    std::vector<half> out(rowValues * static_cast<size_t>(height));
    const char* bytes = static_cast<const char*>(layer.data);
    for (size_t y = 0; y < static_cast<size_t>(height); ++y) {
        const auto* row = reinterpret_cast<const float*>(bytes + y * layer.rowStrideBytes);
        for (size_t i = 0; i < rowValues; ++i) out[y * rowValues + i] = half(row[i]);
    }
    return out;
}

// OpenEXR's global thread pool compresses scanline blocks in parallel. Resizing the pool is not
// free and not meant to race with writers, so it is sized once.
void initThreadPool() {
    static std::once_flag once;
    std::call_once(once, [] {
        Imf::setGlobalThreadCount(static_cast<int>(std::thread::hardware_concurrency()));
    });
}

// Checks the layers against the frame size; returns an error message or "".
std::string validate(int width, int height, const std::vector<ExrLayer>& layers) {
    if (width <= 0 || height <= 0) {
        return "invalid size " + std::to_string(width) + "x" + std::to_string(height);
    }
    if (layers.empty()) return "no layers to write";
    std::set<std::string> names;
    for (const ExrLayer& layer : layers) {
        const std::string label = layer.name.empty() ? "main layer" : "layer '" + layer.name + "'";
        if (layer.channelNames.empty()) return label + " has no channels";
        if (layer.data == nullptr) return label + " has no data";
        const size_t rowBytes = static_cast<size_t>(width) * layer.channelNames.size() * 4;
        if (layer.rowStrideBytes < rowBytes) {
            return label + " row stride " + std::to_string(layer.rowStrideBytes) +
                   " is shorter than a row (" + std::to_string(rowBytes) + " bytes)";
        }
        for (const std::string& channel : layer.channelNames) {
            if (channel.empty()) return label + " has an unnamed channel";
            if (!names.insert(exrChannelName(layer.name, channel)).second) {
                return "channel '" + exrChannelName(layer.name, channel) + "' is written twice";
            }
        }
    }
    return "";
}

}  // namespace

std::string exrChannelName(const std::string& layer, const std::string& channel) {
    if (layer.empty()) return channel;
    if (layer == "depth" && channel == "Z") return "Z";
    return layer + "." + channel;
}

Status writeExr(const std::string& path, int width, int height,
                const std::vector<ExrLayer>& layers, ExrCompression compression) {
    if (std::string problem = validate(width, height, layers); !problem.empty()) {
        return path + ": " + problem;
    }
    initThreadPool();
    try {
        // Header(width, height) sets dataWindow = displayWindow = (0,0)-(width-1,height-1).
        Imf::Header header(width, height);
        header.compression() = toImf(compression);
        Imf::addChromaticities(header, Imf::Chromaticities());  // Rec.709 primaries, D65 white

        Imf::FrameBuffer frameBuffer;
        std::list<std::vector<half>> halfBuffers;  // alive until the pixels are written
        for (const ExrLayer& layer : layers) {
            const Imf::PixelType type = fileType(layer.type);
            const char* base = static_cast<const char*>(layer.data);
            size_t valueBytes = 4;
            size_t rowStride = layer.rowStrideBytes;
            if (type == Imf::HALF) {
                halfBuffers.push_back(toHalf(layer, width, height));
                base = reinterpret_cast<const char*>(halfBuffers.back().data());
                valueBytes = sizeof(half);
                rowStride = static_cast<size_t>(width) * layer.channelNames.size() * sizeof(half);
            }
            const size_t pixelBytes = layer.channelNames.size() * valueBytes;
            for (size_t c = 0; c < layer.channelNames.size(); ++c) {
                const std::string name = exrChannelName(layer.name, layer.channelNames[c]);
                header.channels().insert(name, Imf::Channel(type));
                // OpenEXR's Slice takes a non-const pointer for both reading and writing;
                // an output file only reads through it.
                frameBuffer.insert(name, Imf::Slice(type, const_cast<char*>(base + c * valueBytes),
                                                    pixelBytes, rowStride));
            }
        }

        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frameBuffer);
        file.writePixels(height);
    } catch (const std::exception& e) {
        return path + ": cannot write EXR: " + e.what();
    }
    return std::monostate{};
}

}  // namespace obscura::image
