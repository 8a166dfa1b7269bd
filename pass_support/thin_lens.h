// The physical camera of depth of field (seed 000, "Depth of field"): the circle of confusion of a
// thin lens and the shape of its aperture. The post-process filter (depth_of_field.h) and the
// reference mode's lens sampling (the delegate's accumulation of sub-frames) share these, and
// shaders/common/dof_common.glsl mirrors the aperture mapping for the GPU: change them together.
#pragma once

#include <array>

namespace obscura::passes {

// A lens as USD's camera describes it, in scene units (USD's tenths of a scene unit converted).
struct ThinLens {
    double focalLength = 0.0;    // F
    double fStop = 0.0;          // f = F / A; 0: a pinhole, no depth of field (as in USD)
    double focusDistance = 0.0;  // P, from the lens to the plane in focus
    double filmWidth = 0.0;      // the film gate the image spans horizontally (after conforming)
};

// True when the lens blurs anything: fStop > 0 and a focus plane beyond the focal length (a plane
// at or inside F has no real image, so the thin-lens equation has no answer there).
bool hasDepthOfField(const ThinLens& lens);

// Aperture diameter A = F / f.
double apertureDiameter(const ThinLens& lens);

// Diameter of the circle of confusion of a point at distance D along the view axis, on the film
// the field of view is measured on, in scene units. USD fixes the field of view by F alone (no
// focus breathing), so the film lies at F: a lens of diameter A = F / f focused at P spreads the
// point over A F |1/D - 1/P| there, as path tracers' thin lenses do (Cycles, RenderMan: lens radius
// F / 2f, rays through the focus plane). Potmesil & Chakravarty's CoC (seed 000 "Lens review (2)")
// lies on a film at the image distance I = F P / (P - F), where the same field of view would need a
// film I / F wider: measured against the image, both are A F |1/D - 1/P| / film width.
double circleOfConfusionDiameter(const ThinLens& lens, double distance);

// The lens diameter of an accumulation-buffer camera (pinholes spread over the lens, projecting
// onto a film at the focal length, the focus plane held fixed: the reference mode and a still's
// frames) whose blur is the CoC above: A itself; 0 where the lens does not blur.
double accumulationApertureDiameter(const ThinLens& lens);

// The CoC above is affine in 1/D, and a perspective depth buffer is affine in 1/D too (1/D = 1/near
// + depth * (1/far - 1/near)), so the signed CoC radius in pixels is one multiply-add per pixel:
// radius = depth * scale + bias ("folds down into a single mad in shader"). Positive in front of
// the focus plane (near field), negative behind it.
struct CocFromDepth {
    double scale = 0.0;
    double bias = 0.0;
    double radiusPixels(double depth) const { return depth * scale + bias; }
};
CocFromDepth cocFromDepth(const ThinLens& lens, double nearClip, double farClip, double imageWidthPixels);

// The diaphragm (seed 000 "Plausible DOF: Bokeh", "Sampling"): `blades` straight blades (0: a
// circle) rotated by `rotation`. Straight blades make a regular polygon at every f-stop, as path
// tracers' bladed apertures do (Cycles, RenderMan); the seed's rounding of the polygon wide open
// models curved blades, which USD's camera does not describe.
struct ApertureShape {
    int blades = 0;
    double rotation = 0.0;  // radians, counter-clockwise; the slide's theta_shutter_max
};

ApertureShape apertureShape(int blades, double rotationDegrees);

// A point of the unit square [-1, 1]^2 on the aperture, whose circumscribed circle is the unit
// disc (x right, y up as seen from behind the camera), area-preserving, so that evenly spread
// square points cover the aperture evenly (a flat bokeh kernel, "Plausible DOF: Bokeh"):
// 1. concentric mapping (Shirley & Chiu 1997), square -> disc: in the first region r = a,
//    theta = pi b / (4 a);
// 2. diaphragm: within the sector of each blade (half-angle pi / n about the middle of its edge,
//    which at rotation 0 faces +x), the angle phi is redistributed as tan(phi) is uniform, the
//    density the polygon's area has along its angle (r_max(phi)^2 ~ 1 / cos^2 phi), and the radius
//    scaled to the edge, r cos(pi / n) / cos(phi): the polygon inscribed in the unit circle.
std::array<double, 2> sampleAperture(std::array<double, 2> square, const ApertureShape& shape);

// A cell of the square [-1, 1]^2 before the mapping above: the part of the aperture a still's
// accumulated frame looks through (renderer/reference_frames.h stillLensSample), whose depth of
// field spreads the frame over that part alone. The whole square is the whole aperture.
struct ApertureCell {
    std::array<double, 2> centre{0.0, 0.0};
    std::array<double, 2> halfSize{1.0, 1.0};
    // The cell's linear size relative to the aperture's: the square root of its share of the area.
    double share() const;
};

// How far the cell's points lie from its centre's point at most, on the unit aperture (1 for the
// whole aperture): the reach of a kernel over the cell, per unit of CoC radius.
double apertureCellReach(const ApertureCell& cell, const ApertureShape& shape);

// The centre of cell `index` (row-major) of a side x side grid over [-1, 1]^2: the gather passes'
// taps (a square kernel, seed 000 "Sampling") before the mapping above.
std::array<double, 2> squareGridCell(int index, int side);

}  // namespace obscura::passes
