// The USD camera's frustum: focal length and aperture give the field of view, the "fit"
// conform policy keeps the whole aperture, depth maps near to 0 and far to 1.
#include "delegate/prims/camera.h"
#include "schemas/camera_depth.h"

#include <gtest/gtest.h>

#include <limits>

namespace obscura::delegate {
namespace {

struct ProjectedPoint {
    double x, y, depth;
};

ProjectedPoint project(const Matrix4d& proj, Vec3d viewPoint) {
    double v[4] = {viewPoint[0], viewPoint[1], viewPoint[2], 1.0}, c[4] = {0, 0, 0, 0};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) c[j] += v[i] * proj[i * 4 + j];
    return {c[0] / c[3], c[1] / c[3], c[2] / c[3]};
}

class CameraTest : public ::testing::Test {
protected:
    static const schema::PrimSchema& schema() { return *schema::findPrimSchema("camera"); }
};

TEST_F(CameraTest, FieldOfViewFromFocalLengthAndAperture) {
    Camera cam("/Camera", schema());
    // Default USD camera: 50 mm lens, 20.955 mm aperture; a square image fits the horizontal aperture.
    Matrix4d p = cam.projectionMatrix(1.0);
    double tanHalf = (20.955 / 2.0) / 50.0;
    auto edge = project(p, {tanHalf * 10.0, 0.0, -10.0});
    EXPECT_NEAR(edge.x, 1.0, 1e-9);
    auto top = project(p, {0.0, tanHalf * 10.0, -10.0});
    EXPECT_NEAR(top.y, -1.0, 1e-9) << "Vulkan's y points down";
}

TEST_F(CameraTest, FitKeepsTheWholeAperture) {
    Camera cam("/Camera", schema());
    // A wide image: the vertical aperture (15.2908) stays, the horizontal one widens.
    Matrix4d p = cam.projectionMatrix(2.0);
    double tanHalfV = (15.2908 / 2.0) / 50.0;
    EXPECT_NEAR(project(p, {0.0, tanHalfV * 10.0, -10.0}).y, -1.0, 1e-9);
    EXPECT_NEAR(project(p, {2.0 * tanHalfV * 10.0, 0.0, -10.0}).x, 1.0, 1e-9);
}

TEST_F(CameraTest, DepthRangeIsZeroToOne) {
    Camera cam("/Camera", schema());
    Matrix4d p = cam.projectionMatrix(1.0);
    EXPECT_NEAR(project(p, {0, 0, -1.0}).depth, 0.0, 1e-9);          // default near = 1
    EXPECT_NEAR(project(p, {0, 0, -1000000.0}).depth, 1.0, 1e-9);    // default far = 1e6
}

}  // namespace
}  // namespace obscura::delegate

namespace obscura::delegate {
namespace {

// The depth AOV turns back into distances along the view axis with the schema's conversion, the
// one the projection is built from (schemas/camera_depth.h): a host writing EXR Z gets the distance.
TEST(CameraDepth, DistancesComeBackFromTheDepthTheProjectionGives) {
    Camera cam("/Camera", *schema::findPrimSchema("camera"));  // nothing authored: the schema's defaults
    const Matrix4d p = cam.projectionMatrix(1.0);
    const schema::CameraDepth defaults = schema::defaultCameraDepth();
    EXPECT_FALSE(defaults.orthographic);
    for (double distance : {1.0, 1.5, 10.0, 1234.0, 999999.0}) {
        const double depth = project(p, {0.0, 0.0, -distance}).depth;
        EXPECT_NEAR(schema::viewDistance(depth, defaults), distance, distance * 1e-9) << distance;
    }
    EXPECT_EQ(schema::viewDistance(1.0, defaults), std::numeric_limits<double>::infinity()) << "nothing drew";
    // Orthographic: depth is linear between the clipping planes.
    const schema::CameraDepth ortho{true, 0.5, 100.5};
    const schema::DepthRow row = schema::depthRow(ortho);
    for (double distance : {0.5, 10.0, 100.0}) {
        double depth = row.scale * -distance + row.offset;
        EXPECT_NEAR(depth, (distance - 0.5) / 100.0, 1e-12);
        EXPECT_NEAR(schema::viewDistance(depth, ortho), distance, 1e-9);
    }
}

}  // namespace
}  // namespace obscura::delegate
