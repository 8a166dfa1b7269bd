// Prims of schemas no viewport draws (UsdPhysics' scene, joints and collision groups, UsdMedia's
// SpatialAudio, UsdUI's Backdrop, UsdVol's field assets) organise a scene: the host serves nothing
// for them and reports nothing, while a type it would have to draw (a Volume) is still reported.
#include "tests/delegate/hosted_stage.h"

#include <gtest/gtest.h>

namespace obscura::test {
namespace {

TEST(NonDrawablePrims, SimulationAudioAndUiPrimsAreNotReported) {
    HostedStage scene(usda::Stage::openFromString("#usda 1.0\n" + usdaCamera() + R"(
def PhysicsScene "Physics"
{
    vector3f physics:gravityDirection = (0, -1, 0)
}
def PhysicsCollisionGroup "Group"
{
}
def PhysicsRevoluteJoint "Hinge"
{
    uniform token physics:axis = "Y"
}
def PhysicsFixedJoint "Weld"
{
}
def SpatialAudio "Music"
{
    uniform asset filePath = @music.wav@
}
def Backdrop "Notes"
{
}
def Mesh "Ground"
{
    point3f[] points = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
}
def Volume "Cloud"
{
    rel field:density = </Cloud/Density>
    def OpenVDBAsset "Density"
    {
        asset filePath = @cloud.vdb@
        token fieldName = "density"
    }
}
)",
                                                  "non_drawable.usda"));
    scene.renderAlbedo();
    EXPECT_EQ(scene.lastStatus, OBSCURA_OK);
    EXPECT_EQ(scene.messagesWith("not supported"), 1u);
    EXPECT_TRUE(scene.warned("prim type 'Volume' is not supported yet"));
}

}  // namespace
}  // namespace obscura::test
