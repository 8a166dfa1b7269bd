// Graded charts for tests: the neutral chart of <obscura/grading_chart.h> with a grade applied to
// every value, saved as 8 bits the way an image editor saves a graded screenshot.
#pragma once

#include <functional>
#include <string>

namespace obscura::test {

// Writes the chart to a temporary PNG named after `name`, with `extra` pixels of flat grey
// screenshot right of and below it; returns the path.
std::string writeGradedChart(const std::string& name, const std::function<float(float)>& grade, int extra = 0);

}  // namespace obscura::test
