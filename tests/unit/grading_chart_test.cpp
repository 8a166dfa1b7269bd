// Reading the graded chart back (renderer/grading_chart.h): the neutral chart is the identity
// lattice and a known curve applied to the chart is recovered at every lattice point, each within
// one 8-bit step (the chart's storage).
#include "renderer/grading_chart.h"
#include "tests/support/grading_chart_writer.h"

#include <obscura/grading_chart.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace obscura::test {
namespace {

void expectLattice(const std::string& path, const std::function<float(float)>& grade) {
    auto read = renderer::readGradingChart(path);
    ASSERT_TRUE(std::holds_alternative<passes::GradingLattice>(read)) << std::get<std::string>(read);
    const auto& lattice = std::get<passes::GradingLattice>(read);
    ASSERT_EQ(lattice.size, OBSCURA_GRADING_CHART_LATTICE);
    for (uint32_t b = 0; b < lattice.size; ++b)
        for (uint32_t g = 0; g < lattice.size; ++g)
            for (uint32_t r = 0; r < lattice.size; ++r) {
                const uint32_t index[3] = {r, g, b};
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(lattice.at(r, g, b)[c], grade(index[c] / 15.0f), 1.0f / 255.0f)
                        << "lattice point " << r << " " << g << " " << b << ", channel " << c;
            }
    std::filesystem::remove(path);
}

TEST(GradingChart, NeutralChartInAScreenshotIsTheIdentity) {
    auto identity = [](float v) { return v; };
    expectLattice(writeGradedChart("neutral_chart", identity, 40), identity);
}

TEST(GradingChart, AGammaAppliedToTheChartIsRecoveredAtEveryLatticePoint) {
    auto gamma = [](float v) { return std::pow(v, 1.2f); };
    expectLattice(writeGradedChart("gamma_chart", gamma), gamma);
}

TEST(GradingChart, AnUnreadableFileIsRefusedWithTheReason) {
    auto read = renderer::readGradingChart("/nonexistent/chart.png");
    ASSERT_TRUE(std::holds_alternative<std::string>(read));
    EXPECT_NE(std::get<std::string>(read).find("cannot read image"), std::string::npos);
}

}  // namespace
}  // namespace obscura::test
