// OBSCURA_PIPELINE_STATISTICS (gpu/pipeline_statistics.h): asking for the drivers' statistics
// changes nothing of the frame, on a device that reports them and on one that does not (lavapipe
// lacks VK_KHR_pipeline_executable_properties); where they are reported, every pipeline is, the
// lighting pass's among them.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

namespace obscura::test {
namespace {

std::vector<float> renderLitPlane(std::vector<std::string>* infos) {
    LitPlaneScene s;
    s.host.addPrim("sphereLight", "/Bulb",
                   {{"inputs:intensity", HostValue::floatValue(50.0f)}, {"inputs:radius", HostValue::floatValue(0.1f)}},
                   translation(0.3, -0.2, 1.0));
    std::vector<float> color = s.renderColor();
    if (infos) *infos = s.host.loggedInfos();
    return color;
}

TEST(PipelineStatistics, AskingChangesNothingOfTheFrame) {
    const std::vector<float> plain = renderLitPlane(nullptr);
    setenv("OBSCURA_PIPELINE_STATISTICS", "1", 1);
    std::vector<std::string> infos;
    const std::vector<float> asked = renderLitPlane(&infos);
    unsetenv("OBSCURA_PIPELINE_STATISTICS");
    EXPECT_EQ(plain, asked);
    const auto reported = std::count_if(infos.begin(), infos.end(), [](const std::string& line) {
        return line.find("pipeline statistics: ") != std::string::npos;
    });
    if (reported > 0) {
        EXPECT_TRUE(std::any_of(infos.begin(), infos.end(), [](const std::string& line) {
            return line.find("pipeline statistics: lighting") != std::string::npos;
        }));
    }
}

}  // namespace
}  // namespace obscura::test
