// The errors a delegate test provokes on purpose, declared by the test: any other error the plugin
// logs fails the test, and so does a declared error that never came (hdEmbree's tests fail on any
// posted error; STYLE.md, "Three layers of tests").
#pragma once

#include <string>
#include <vector>

namespace obscura::test {

class ExpectedErrors {
public:
    // A logged error containing `fragment` is one the test provokes.
    void add(std::string fragment) { fragments_.push_back(std::move(fragment)); }
    // Fails the running test once for every logged error no fragment matches and every fragment
    // no logged error matched. `who` names the host in the failure.
    void check(const std::vector<std::string>& logged, const std::string& who) const;

private:
    std::vector<std::string> fragments_;
};

}  // namespace obscura::test
