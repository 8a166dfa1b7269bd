#include "delegate/prims/light.h"

#include "pass_support/thin_lens.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {

namespace {

// UsdLuxDomeLight inputs:texture:format: "automatic" reads the file as latlong, warning when its
// shape is not 2:1 (the other layouts are square or 3:4).
TexturePtr readDomeTexture(SceneAccess& s, TextureCache& textures, std::string& warning) {
    const std::string file = s.getToken("inputs:texture:file");
    if (file.empty()) return nullptr;
    const std::string format = s.getToken("inputs:texture:format");
    if (format != "automatic" && format != "latlong") {
        warning = "inputs:texture:format '" + format + "' is not supported (only latlong); the dome uses its constant colour";
        return nullptr;
    }
    // Float files are linear; 8-bit ones are decoded as their channel count suggests.
    auto loaded = textures.get(file, SourceColorSpace::Auto, TextureRole::Plain);
    if (auto* problem = std::get_if<std::string>(&loaded)) {
        warning = "cannot read inputs:texture:file " + file + " (" + *problem + "); the dome uses its constant colour";
        return nullptr;
    }
    TexturePtr texture = std::get<TexturePtr>(loaded);
    const gpu::ImageDesc& desc = texture->image->desc;
    if (format == "automatic" && desc.width != 2 * desc.height)
        warning = file + " is " + std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                  ", not the 2:1 of a latlong map; it is read as one";
    return texture;
}

}  // namespace

void Light::pull(SceneAccess& s, ObscuraDirtyBits, SyncContext& ctx) {
    if (s.dirty("transform")) {
        transform_ = s.sampleTransform(s.time(), s.time()).front().matrix;
        shutterTransforms_ = s.sampleTransform(ctx.shutterOpen, ctx.shutterClose);
    }
    if (s.dirty("visibility")) visible_ = s.getToken("visibility") != "invisible";
    // The emission and shape are placed by the transform: either changing places them again.
    if (!s.anyDirtyBut({"visibility"})) return;

    const double pi = std::numbers::pi;
    double intensity = s.getDouble("inputs:intensity") * std::exp2(s.getDouble("inputs:exposure"));
    auto color = s.getFloat3("inputs:color");
    if (s.getBool("inputs:enableColorTemperature")) {
        auto tint = blackbodyColor(s.getDouble("inputs:colorTemperature"));
        for (size_t i = 0; i < 3; ++i) color[i] *= tint[i];
    }
    castsShadows_ = type_ != passes::LightType::Dome && s.getBool("inputs:shadow:enable");
    clipVolume_ = s.getPath("obscura:clipVolume");
    Shape shape;
    shape.normalize = s.getBool("inputs:normalize");
    for (size_t i = 0; i < 3; ++i) shape.radiance[i] = intensity * color[i];
    shape.factors = {s.getFloat("inputs:diffuse"), s.getFloat("inputs:specular"), 0.0f, 0.0f};
    warning_.clear();
    if (type_ == passes::LightType::Dome) {
        // The texture's texels are radiance, scaled like the constant colour (UsdLux); the frame
        // marks the dome that lights through it (factors.z) and orients it by the transform.
        environment_ = readDomeTexture(s, ctx.textures, warning_);
    } else if (type_ == passes::LightType::Distant) {
        shape.angle = s.getDouble("inputs:angle") * pi / 180.0;
    } else {
        if (type_ == passes::LightType::Sphere) {
            shape.halfX = s.getDouble("inputs:radius");
            if (shape.halfX <= 0) throw PrimDataError(s.path() + ": inputs:radius must be positive");
            shape.factors[2] = s.getBool("treatAsPoint") ? 1.0f : 0.0f;
        } else if (type_ == passes::LightType::Cylinder) {
            shape.halfX = 0.5 * s.getDouble("inputs:length");
            shape.halfY = s.getDouble("inputs:radius");
            if (shape.halfX <= 0 || shape.halfY <= 0)
                throw PrimDataError(s.path() + ": inputs:length and inputs:radius must be positive");
            shape.factors[2] = s.getBool("treatAsLine") ? 1.0f : 0.0f;
        } else if (type_ == passes::LightType::Rect) {
            shape.halfX = 0.5 * s.getDouble("inputs:width");
            shape.halfY = 0.5 * s.getDouble("inputs:height");
            if (shape.halfX <= 0 || shape.halfY <= 0)
                throw PrimDataError(s.path() + ": inputs:width and inputs:height must be positive");
        } else {
            shape.halfX = shape.halfY = s.getDouble("inputs:radius");
            if (shape.halfX <= 0) throw PrimDataError(s.path() + ": inputs:radius must be positive");
        }
        // ShapingAPI: the fade starts at lerp(softness, cutoff, 0) (UsdLuxShapingAPI). A cylinder
        // has no shaping inputs (its schema): it emits all around its axis, unshaped.
        shape.shaping = {float(pi), float(pi), 0.0f, 0.0f};
        if (type_ != passes::LightType::Cylinder) {
            double cone = std::clamp(double(s.getFloat("inputs:shaping:cone:angle")), 0.0, 180.0) * pi / 180.0;
            double softness = std::clamp(double(s.getFloat("inputs:shaping:cone:softness")), 0.0, 1.0);
            double focus = std::max(0.0, double(s.getFloat("inputs:shaping:focus")));
            shape.shaping = {float(cone), float(cone * (1.0 - softness)), float(focus), 0.0f};
        }
    }
    shape_ = shape;
    data_ = placed(transform_);
    if (type_ != passes::LightType::Dome && type_ != passes::LightType::Distant && data_.radiance[3] < 0.0f)
        throw PrimDataError(s.path() + ": the transform collapses the light to zero area");
}

passes::LightData Light::dataAt(double time) const {
    return shutterTransforms_.size() > 1 ? placed(interpolateTransform(shutterTransforms_, time)) : data_;
}

passes::LightData Light::placed(const Matrix4d& transform) const {
    const double pi = std::numbers::pi;
    passes::LightData d{};
    d.factors = shape_.factors;
    double scale = 1.0;
    if (type_ == passes::LightType::Dome) {
        d.positionType = {0, 0, 0, float(passes::LightType::Dome)};
    } else if (type_ == passes::LightType::Distant) {
        double solidAngle = 2.0 * pi * (1.0 - std::cos(shape_.angle / 2.0));
        scale = shape_.normalize ? 1.0 : solidAngle;
        // UsdLux lights emit along their local -Z axis.
        Vec3d dir = normalized(transformDirection({0, 0, -1}, transform));
        d.positionType = {0, 0, 0, float(passes::LightType::Distant)};
        d.directionAngle = {float(dir[0]), float(dir[1]), float(dir[2]), float(shape_.angle / 2.0)};
    } else {
        // UsdLux lights emit along their local -Z axis; the transform's scale scales their size.
        Vec3d axis = normalized(transformDirection({0, 0, -1}, transform));
        Vec3d pos = transformPoint({0, 0, 0}, transform);
        Vec3d localX = transformDirection({1, 0, 0}, transform), localY = transformDirection({0, 1, 0}, transform);
        d.positionType = {float(pos[0]), float(pos[1]), float(pos[2]), float(type_)};
        d.directionAngle = {float(axis[0]), float(axis[1]), float(axis[2]), 0.0f};
        d.shaping = shape_.shaping;
        double area = 0.0;
        if (type_ == passes::LightType::Sphere) {
            double axisScale = std::max({length(localX), length(localY), length(transformDirection({0, 0, 1}, transform))});
            double radius = shape_.halfX * axisScale;
            area = 4.0 * pi * radius * radius;
            d.radiance[3] = float(radius);
        } else if (type_ == passes::LightType::Cylinder) {
            // Along local X; the radius scales with the larger of the two scales across it.
            Vec3d halfLength = {localX[0] * shape_.halfX, localX[1] * shape_.halfX, localX[2] * shape_.halfX};
            double radius = shape_.halfY * std::max(length(localY), length(transformDirection({0, 0, 1}, transform)));
            area = 2.0 * pi * radius * 2.0 * length(halfLength);
            d.radiance[3] = float(radius);
            d.axisX = {float(halfLength[0]), float(halfLength[1]), float(halfLength[2]), 0.0f};
        } else {
            // The disk's (or rectangle's) half extents along its local X and Y, in world space.
            double lengths = length(localX) * length(localY);
            area = (type_ == passes::LightType::Rect ? 4.0 : pi) * shape_.halfX * shape_.halfY * lengths;
            d.axisX = {float(localX[0] * shape_.halfX), float(localX[1] * shape_.halfX), float(localX[2] * shape_.halfX), 0.0f};
            d.axisY = {float(localY[0] * shape_.halfY), float(localY[1] * shape_.halfY), float(localY[2] * shape_.halfY), 0.0f};
        }
        // A collapsed light emits nothing; pull() reports it (radiance.w < 0 marks it).
        if (area <= 0) {
            d.radiance = {0.0f, 0.0f, 0.0f, -1.0f};
            return d;
        }
        if (shape_.normalize) scale = 1.0 / area;
    }
    for (int i = 0; i < 3; ++i) d.radiance[size_t(i)] = float(shape_.radiance[size_t(i)] * scale);
    return d;
}

passes::LightData withInfluenceRange(passes::LightData light, double exposureScale) {
    auto type = passes::LightType(uint32_t(light.positionType[3]));
    if (type == passes::LightType::Distant || type == passes::LightType::Dome) return light;
    // Beyond this distance the light's irradiance, pre-exposed, is below 2^-12 (a quarter of an
    // 8-bit sRGB step just above black): E <= L * A_projected / d^2, with A_projected = pi r^2
    // for a sphere, the area for a rectangle or disk, length x diameter for a cylinder.
    const double threshold = 1.0 / 4096.0;
    double radiance = std::max({light.radiance[0], light.radiance[1], light.radiance[2]}) * exposureScale;
    double size = 0.0, projectedArea = 0.0;
    if (type == passes::LightType::Sphere) {
        size = light.radiance[3];
        projectedArea = std::numbers::pi * size * size;
    } else if (type == passes::LightType::Cylinder) {
        // Seen across its axis: its length by its diameter.
        double halfLength = std::hypot(light.axisX[0], light.axisX[1], light.axisX[2]);
        size = std::hypot(halfLength, double(light.radiance[3]));
        projectedArea = 4.0 * halfLength * light.radiance[3];
    } else {
        Vec3d x{light.axisX[0], light.axisX[1], light.axisX[2]}, y{light.axisY[0], light.axisY[1], light.axisY[2]};
        size = std::hypot(length(x), length(y));
        projectedArea = (type == passes::LightType::Rect ? 4.0 : std::numbers::pi) * length(x) * length(y);
    }
    light.factors[3] = float(std::max(size, std::sqrt(radiance * projectedArea / threshold)));
    return light;
}

double brightestIrradiance(const passes::LightData& light) {
    const double brightest = std::max({light.radiance[0], light.radiance[1], light.radiance[2], 0.0f});
    // A distant light's record holds its irradiance (placed: its radiance times its solid angle,
    // or as given where normalised).
    if (passes::LightType(uint32_t(light.positionType[3])) == passes::LightType::Distant) return brightest;
    return std::numbers::pi * brightest;
}

passes::LightData emitterSample(const passes::LightData& light, std::array<double, 2> u) {
    auto type = passes::LightType(uint32_t(light.positionType[3]));
    if (type == passes::LightType::Distant) {
        double halfAngle = light.directionAngle[3];
        if (halfAngle <= 0.0) return light;
        Vec3d axis = {light.directionAngle[0], light.directionAngle[1], light.directionAngle[2]};
        Vec3d tangent = normalized(cross(std::abs(axis[1]) < 0.99 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0}, axis));
        Vec3d bitangent = cross(axis, tangent);
        // Area-preserving square -> disc (Shirley & Chiu 1997, shared with the lens); a share rho^2
        // of the disc's area maps to the same share of the cone's solid angle.
        auto [x, y] = passes::sampleAperture({2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0}, {});
        double rho2 = x * x + y * y, cosTheta = 1.0 - rho2 * (1.0 - std::cos(halfAngle));
        double sinOverRho = rho2 > 0.0 ? std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta) / rho2) : 0.0;
        Vec3d d = add(scale(axis, cosTheta), scale(add(scale(tangent, x), scale(bitangent, y)), sinOverRho));
        passes::LightData sample = light;
        sample.directionAngle = {float(d[0]), float(d[1]), float(d[2]), 0.0f};
        return sample;
    }
    // XXX: sphere, rect, disk and cylinder lights stay whole (the lighting pass's closed forms, hard shadows
    // from their centre): a point of the surface per sub-frame, weighted by its cosine towards the
    // receiver, left a moving bulb's 128-sub-frame mean 3-8% off its closed form
    // (ReferenceShutter.MovingLightIsAveragedOverItsPath asks for 1%).
    return light;
}

std::array<float, 3> blackbodyColor(double kelvin) {
    double t = std::clamp(kelvin, 1000.0, 40000.0);
    // Planckian locus in CIE 1960 uv (Krystek 1985), then xy and XYZ with Y = 1.
    double u = (0.860117757 + 1.54118254e-4 * t + 1.28641212e-7 * t * t) / (1.0 + 8.42420235e-4 * t + 7.08145163e-7 * t * t);
    double v = (0.317398726 + 4.22806245e-5 * t + 4.20481691e-8 * t * t) / (1.0 - 2.89741816e-5 * t + 1.61456053e-7 * t * t);
    double x = 3.0 * u / (2.0 * u - 8.0 * v + 4.0), y = 2.0 * v / (2.0 * u - 8.0 * v + 4.0);
    double X = x / y, Y = 1.0, Z = (1.0 - x - y) / y;
    // XYZ to linear Rec.709 (D65).
    std::array<double, 3> rgb = {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
                                 -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                                 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
    for (auto& c : rgb) c = std::max(c, 0.0);
    double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    return {float(rgb[0] / luminance), float(rgb[1] / luminance), float(rgb[2] / luminance)};
}

}  // namespace obscura::delegate
