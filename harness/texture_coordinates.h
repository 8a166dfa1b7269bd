// Affine maps of texture coordinates, as UsdTransform2d shaders and MaterialX's tiled images put
// them between a mesh's primvar and a texture lookup; served to the delegate as the rows of
// obscura:<input>:transformS and transformT (schemas/material.json).
#pragma once

#include <array>
#include <optional>

namespace obscura::harness {

// st' = (dot(s, (s, t, 1)), dot(t, (s, t, 1))).
struct StTransform {
    std::array<double, 3> s{1.0, 0.0, 0.0};
    std::array<double, 3> t{0.0, 1.0, 0.0};
};

// `outer` applied to what `inner` gives: a chain of transforms folded into one.
StTransform compose(const StTransform& outer, const StTransform& inner);

// UsdTransform2d (UsdPreviewSurface spec): st' = translation + rotate(rotation) (scale st), the
// rotation counter-clockwise in degrees.
StTransform transform2d(std::array<double, 2> scale, double rotationDegrees, std::array<double, 2> translation);

// MaterialX ND_tiledimage (its NG_tiledimage graph): uv' = (uv uvtiling - uvoffset) /
// realworldimagesize * realworldtilesize; nullopt when the result is not finite (a zero image size).
std::optional<StTransform> tiledImage(std::array<double, 2> uvtiling, std::array<double, 2> uvoffset,
                                      std::array<double, 2> realworldimagesize,
                                      std::array<double, 2> realworldtilesize);

bool isFinite(const StTransform& transform);

}  // namespace obscura::harness
