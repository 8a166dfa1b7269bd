// Writes a frame and its AOVs as ONE single-part, multi-channel OpenEXR file, the layout
// compositors (Nuke, Blender, oiiotool) read as layers of one image.
//
// Channel names in the file:
//   - the unnamed layer ("")            -> its channel names as given: R, G, B, A;
//   - layer "depth" with channel "Z"    -> plain "Z", the name compositors look for;
//   - any other layer                   -> "<layer>.<channel>", e.g. normal.X, primId.id.
//
// Integer AOVs (primId, -1 = nothing hit) are stored as UINT channels holding the bit pattern
// of the int32 value: -1 is stored as 0xFFFFFFFF. EXR has no signed integer type; readers that
// know the convention (exr_reader.h does) reinterpret the bits as int32.
//
// The header carries dataWindow = displayWindow = (0,0)-(width-1,height-1) and the Rec.709 / D65
// chromaticities, so tools treat the pixels as scene-linear Rec.709.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "harness/image/image.h"

namespace obscura::image {

struct ExrLayer {
    enum class PixelType {
        Half,    // given as float data, rounded to the nearest half (beyond +-65504: inf)
        Float,   // float data, stored as 32-bit float
        Uint,    // uint32 (or int32 bit pattern) data, stored as UINT
    };

    std::string name;                       // "" for the main RGBA, else "normal", "depth", ...
    std::vector<std::string> channelNames;  // {"R","G","B","A"}, {"Z"}, {"X","Y","Z"}, {"id"}
    PixelType type = PixelType::Float;
    const void* data = nullptr;             // interleaved: channelNames.size() values per pixel,
                                            // 4 bytes each (float, or uint32 for Uint)
    size_t rowStrideBytes = 0;              // distance between rows; rows are top row first
};

enum class ExrCompression { None, Zip, Zips, Piz, Rle };

// The file channel name for a layer's channel, following the rules above.
std::string exrChannelName(const std::string& layer, const std::string& channel);

// Writes all layers of a width x height frame to `path`. Fails (with nothing thrown) on invalid
// layers: no data, no channels, a row stride shorter than a row, or two layers producing the same
// channel name; and on any I/O error.
Status writeExr(const std::string& path, int width, int height,
                const std::vector<ExrLayer>& layers,
                ExrCompression compression = ExrCompression::Zip);

}  // namespace obscura::image
