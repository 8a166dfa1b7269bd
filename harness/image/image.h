// A float image in memory, the one type every reader returns and the comparison works on,
// and the result type of the image API: functions return a value or a readable error string
// instead of throwing (library exceptions are caught inside).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace obscura::image {

// Either a value or an error message. Errors name the file they are about.
template <class T>
using Result = std::variant<T, std::string>;

// The result of an operation that returns nothing but can fail.
using Status = Result<std::monostate>;

template <class T>
bool isError(const Result<T>& r) { return std::holds_alternative<std::string>(r); }

template <class T>
const std::string& errorOf(const Result<T>& r) { return std::get<std::string>(r); }

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::string> channels;   // "R", "G", "B", "A", "Z", "normal.X", ...
    std::vector<float> pixels;           // interleaved, row-major, top row first

    // A zero-filled image of the given size and channels.
    static Image make(int w, int h, std::vector<std::string> channelNames) {
        Image img;
        img.width = w;
        img.height = h;
        img.channels = std::move(channelNames);
        img.pixels.assign(static_cast<size_t>(w) * static_cast<size_t>(h) * img.channels.size(),
                          0.0f);
        return img;
    }

    size_t channelCount() const { return channels.size(); }

    // Index of a channel by exact name, or -1 when the image has no such channel.
    int channelIndex(std::string_view name) const {
        for (size_t i = 0; i < channels.size(); ++i) {
            if (channels[i] == name) return static_cast<int>(i);
        }
        return -1;
    }
    bool hasChannel(std::string_view name) const { return channelIndex(name) >= 0; }

    size_t index(int x, int y, int channel) const {
        return (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) *
                   channels.size() +
               static_cast<size_t>(channel);
    }
    float& at(int x, int y, int channel) { return pixels[index(x, y, channel)]; }
    float at(int x, int y, int channel) const { return pixels[index(x, y, channel)]; }
};

}  // namespace obscura::image
