// Cameras (UsdGeomCamera) and lights (UsdLux), each a child prim of its node carrying the local
// frame Assimp gives it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "harness/import/convert.h"

namespace obscura::harness::importer {

namespace {

// A film back 36 wide and as high as the aspect ratio makes it (36 x 24 when the file gives no
// ratio); the field of view sets the focal length against it. USD reads both in tenths of a scene
// unit, and only their ratio shapes a perspective view.
constexpr double kHorizontalAperture = 36.0;
constexpr double kDefaultAspect = 1.5;
// Point and spot lights become spheres this small, in metres.
constexpr double kPointLightRadiusMeters = 0.01;

aiVector3D cross(const aiVector3D& a, const aiVector3D& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The frame at `position` whose -Z is `forward` and whose +Y is `up` made perpendicular to it (any
// perpendicular when `up` is missing or parallel); nullopt when `forward` has no direction.
std::optional<aiMatrix4x4> lookFrame(const aiVector3D& position, const aiVector3D& forward, const aiVector3D& up) {
    if (!isFinite(position) || !isFinite(forward) || !isFinite(up) || forward.Length() <= 0) return std::nullopt;
    const aiVector3D f = aiVector3D(forward).Normalize();
    aiVector3D y = up - f * (up * f);
    if (y.Length() < 1e-6f) {
        const aiVector3D axis = std::abs(f.y) < 0.9f ? aiVector3D(0, 1, 0) : aiVector3D(1, 0, 0);
        y = axis - f * (axis * f);
    }
    y.Normalize();
    const aiVector3D z = -f;
    const aiVector3D x = cross(y, z);
    return aiMatrix4x4(x.x, y.x, z.x, position.x, x.y, y.y, z.y, position.y, x.z, y.z, z.z, position.z, 0, 0, 0, 1);
}

// Assimp's horizontal field of view is the full angle in radians (whatever aiCamera's comment says;
// its FBX and glTF importers write the full angle). Its glTF importer writes yfov * aspect (yfov
// alone without an aspect ratio), not the angle that aspect gives: the glTF yfov is recovered and
// widened by the aspect ratio properly.
double horizontalFov(const Source& source, const aiCamera& camera, double aspect) {
    if (source.format != SourceFormat::Gltf) return camera.mHorizontalFOV;
    const double yfov = camera.mHorizontalFOV / (camera.mAspect > 0 ? camera.mAspect : 1.0f);
    return 2.0 * std::atan(aspect * std::tan(yfov / 2.0));
}

void writeLens(const Source& source, const aiCamera& camera, const std::string& label, UsdaWriter& out,
               Warnings& warnings) {
    const double aspect = camera.mAspect > 0 && std::isfinite(camera.mAspect) ? camera.mAspect : kDefaultAspect;
    if (camera.mOrthographicWidth > 0 && std::isfinite(camera.mOrthographicWidth)) {
        // mOrthographicWidth is half the view's width in scene units.
        const double width = 2.0 * camera.mOrthographicWidth * 10.0;
        out.property("token projection", stringLiteral("orthographic"));
        out.property("float horizontalAperture", number(static_cast<float>(width)));
        out.property("float verticalAperture", number(static_cast<float>(width / aspect)));
        return;
    }
    const double hfov = horizontalFov(source, camera, aspect);
    if (!(hfov > 0 && hfov < std::numbers::pi)) {
        warnings.add(label + ": field of view out of range; USD's default lens used");
        return;
    }
    out.property("token projection", stringLiteral("perspective"));
    out.property("float focalLength", number(static_cast<float>(0.5 * kHorizontalAperture / std::tan(hfov / 2.0))));
    out.property("float horizontalAperture", number(static_cast<float>(kHorizontalAperture)));
    out.property("float verticalAperture", number(static_cast<float>(kHorizontalAperture / aspect)));
}

// Assimp folds a light's intensity into its colour: the brightest channel is the intensity and the
// colour is scaled to it.
struct Emission {
    aiColor3D color;
    double intensity = 0;
};

Emission emissionOf(const aiColor3D& c) {
    const float peak = std::max({c.r, c.g, c.b});
    if (!(peak > 0)) return {aiColor3D(1, 1, 1), 0.0};
    return {aiColor3D(c.r / peak, c.g / peak, c.b / peak), peak};
}

void writeDistantLight(const aiLight& light, const std::string& name, const Emission& emission, UsdaWriter& out,
                       Warnings& warnings) {
    const std::optional<aiMatrix4x4> frame = lookFrame(light.mPosition, light.mDirection, light.mUp);
    if (!frame) {
        warnings.add("light '" + std::string(light.mName.C_Str()) + "': no usable direction; skipped");
        return;
    }
    out.beginPrim("DistantLight", name);
    writeMatrixTransform(*frame, out);
    out.property("color3f inputs:color", tuple({emission.color.r, emission.color.g, emission.color.b}));
    // Normalized with no angular size, the intensity is the irradiance it gives, as for Assimp's
    // (and glTF's) directional lights.
    out.property("float inputs:intensity", number(static_cast<float>(emission.intensity)));
    out.property("float inputs:angle", "0");
    out.property("bool inputs:normalize", "1");
    out.endPrim();
}

void writePointLight(const Source& source, const aiLight& light, const std::string& name, const Emission& emission,
                     UsdaWriter& out, Warnings& warnings) {
    if (!isFinite(light.mPosition)) {
        warnings.add("light '" + std::string(light.mName.C_Str()) + "': non-finite position; skipped");
        return;
    }
    const double radius = kPointLightRadiusMeters / source.metersPerUnit;
    out.beginPrim("SphereLight", name);
    aiMatrix4x4 frame;
    writeMatrixTransform(aiMatrix4x4::Translation(light.mPosition, frame), out);
    out.property("color3f inputs:color", tuple({emission.color.r, emission.color.g, emission.color.b}));
    // A sphere of radiance L and radius r gives the irradiance pi * L * r^2 / d^2 at distance d; a
    // point light of intensity I gives I / d^2, so L = I / (pi * r^2).
    const double radiance = emission.intensity / (std::numbers::pi * radius * radius);
    out.property("float inputs:intensity", number(static_cast<float>(radiance)));
    out.property("float inputs:radius", number(static_cast<float>(radius)));
    out.property("bool treatAsPoint", "1");
    out.endPrim();
}

}  // namespace

void writeCamera(const Source& source, const aiCamera& camera, NameScope& siblings, UsdaWriter& out,
                 Warnings& warnings) {
    const std::string label = "camera '" + std::string(camera.mName.C_Str()) + "'";
    // glTF cameras look down -Z from their node's origin by definition, and Assimp 5.2's glTF importer
    // copies the node's translation into mPosition too, which would apply it twice.
    const std::optional<aiMatrix4x4> frame = source.format == SourceFormat::Gltf
                                                 ? aiMatrix4x4()
                                                 : lookFrame(camera.mPosition, camera.mLookAt, camera.mUp);
    if (!frame) {
        warnings.add(label + ": no usable view direction; skipped");
        return;
    }
    out.beginPrim("Camera", siblings.claim(camera.mName.C_Str(), "Camera"));
    writeMatrixTransform(*frame, out);
    writeLens(source, camera, label, out, warnings);
    const float near = camera.mClipPlaneNear, far = camera.mClipPlaneFar;
    if (near > 0 && far > near && std::isfinite(far)) {
        out.property("float2 clippingRange", tuple({near, far}));
    } else {
        warnings.add(label + ": invalid clipping planes; USD's default range used");
    }
    out.endPrim();
}

void writeLight(const Source& source, const aiLight& light, NameScope& siblings, UsdaWriter& out,
                Warnings& warnings) {
    const std::string label = "light '" + std::string(light.mName.C_Str()) + "'";
    if (!isFinite(light.mColorDiffuse)) {
        warnings.add(label + ": non-finite colour; skipped");
        return;
    }
    const Emission emission = emissionOf(light.mColorDiffuse);
    switch (light.mType) {
    case aiLightSource_DIRECTIONAL:
        writeDistantLight(light, siblings.claim(light.mName.C_Str(), "Light"), emission, out, warnings);
        return;
    case aiLightSource_SPOT:
        warnings.add(label + ": spot cone shaping is not supported yet; imported as a point light");
        [[fallthrough]];
    case aiLightSource_POINT:
        writePointLight(source, light, siblings.claim(light.mName.C_Str(), "Light"), emission, out, warnings);
        return;
    default:
        warnings.add(label + ": area, ambient and undefined lights are not supported; skipped");
        return;
    }
}

}  // namespace obscura::harness::importer
