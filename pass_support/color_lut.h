// The display/view transform baked into a 3D LUT (seed 004 "Color grading": bake all global
// colour transformations into one 3D LUT so the grading pass is a single lookup; Selan 2007,
// GPU Gems 3 ch. 24). CPU side only: OpenColorIO evaluates scene_linear -> display/view (+looks)
// on a lattice, and the GPU pass uploads `rgba` as a 3D texture and samples it after the shaper.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace obscura::passes {

struct ColorLutRequest {
    std::string configPath;  // "" -> $OCIO if set, else the built-in config
    std::string display;     // "" -> the config's default display
    std::string view;        // "" -> the config's default view for the display
    std::string look;        // "" -> only the view's own looks; else OCIO's look syntax ("a, -b"), replacing them
};

// The shaper (Selan 2007: a 3D LUT spans [0,1], so scene-linear HDR goes through a 1D log shaper
// first, which also spends the lattice evenly per stop). With g = kShaperMiddleGrey,
// lo = shaperMinStops and R = shaperMaxStops - lo:
//   log segment:  c(x) = (log2(x / g) - lo) / R
//   linear toe:   the tangent from the origin to the log segment, so 0 -> 0 and the curve is C1.
//                 It touches at xToe = g * 2^(lo + 1/ln 2), where c = cToe = 1 / (R ln 2);
//                 below it c(x) = x * cToe / xToe.
//   c is clamped to [0, 1]; x >= g * 2^shaperMaxStops saturates to 1.
// Decoding inverts each segment: c < cToe -> x = c * xToe / cToe, else x = g * 2^(c R + lo).
constexpr float kShaperMiddleGrey = 0.18f;
// -10 stops puts the toe at ~5e-4; +16 stops (~1.2e4) keeps the ratios of very bright saturated
// colours, which the ACES output transform tone maps per channel, from being clipped by the shaper.
constexpr float kShaperMinStops = -10.0f;
constexpr float kShaperMaxStops = 16.0f;

// The lookup (what the GPU pass does):
//   display = clamp(trilinear(rgba, (shaperEncode(r), shaperEncode(g), shaperEncode(b))), 0, 1)
// rgba holds the view's output unclamped (out-of-gamut colours go below 0, bright ones above 1:
// built-in "Filmic" -0.36..1.08, "Standard" 0..52, "Raw" 0..1.2e4), so it needs a signed float
// format such as R16G16B16A16_SFLOAT. Clamping after the interpolation keeps the clamp's kink out of the lattice
// cells: measured over random HDR colours at 33^3, max error 0.10 -> 0.03 (Filmic) and 0.054 ->
// 0.006 (Standard) against clamping at bake time.
struct ColorLut {
    uint32_t size = 33;       // lattice points per axis
    std::vector<float> rgba;  // size^3 * 4 floats, r fastest, then g, then b (VkImage 3D x=r, y=g, z=b);
                              // alpha 1
    float shaperMinStops = kShaperMinStops;
    float shaperMaxStops = kShaperMaxStops;
    std::string description;  // "config: <name or built-in>, display: X, view: Y, look: Z"
};

// Per channel, before the LUT lookup: linear >= 0 -> [0, 1] (negative input counts as 0).
float shaperEncode(float linear, const ColorLut& lut);
float shaperDecode(float coordinate, const ColorLut& lut);

// For each lattice point: decode the shaper to scene-linear RGB, apply the OCIO processor
// (scene_linear role -> display/view with looks) on the CPU and store the result, unclamped.
// Errors name what was not found (config file, display, view, look) and list the valid choices.
// Configs and processors are cached per request within the process (33^3 bakes in ~4 ms).
std::variant<ColorLut, std::string> bakeColorLut(const ColorLutRequest& request, uint32_t size = 33);

// Reference for tests: the same processor applied to one scene-linear colour (no LUT, no clamp).
std::variant<std::array<float, 3>, std::string> applyViewTransform(const ColorLutRequest& request,
                                                                   std::array<float, 3> linearRgb);

// The built-in config (made in code, no files), an ACES 1.0 style config in OCIO 2.1 built-in
// transforms: scene_linear = linear Rec.709; display "sRGB" with these views, default first:
//   "Filmic"   ACES 1.0 SDR video output transform (RRT + ODT), sRGB piecewise encoding
//   "Standard" linear Rec.709 encoded with the sRGB inverse EOTF (the lookup clamps to [0,1])
//   "Raw"      no transform
std::vector<std::string> builtInViews();

}  // namespace obscura::passes
