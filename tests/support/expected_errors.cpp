#include "tests/support/expected_errors.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace obscura::test {

void ExpectedErrors::check(const std::vector<std::string>& logged, const std::string& who) const {
    auto contains = [](const std::string& message, const std::string& fragment) {
        return message.find(fragment) != std::string::npos;
    };
    for (const std::string& message : logged) {
        bool declared = std::any_of(fragments_.begin(), fragments_.end(),
                                    [&](const std::string& fragment) { return contains(message, fragment); });
        if (!declared) ADD_FAILURE() << who << " logged an error the test did not declare: " << message;
    }
    for (const std::string& fragment : fragments_) {
        bool came = std::any_of(logged.begin(), logged.end(),
                                [&](const std::string& message) { return contains(message, fragment); });
        if (!came) ADD_FAILURE() << who << " never logged the error the test declared: \"" << fragment << "\"";
    }
}

}  // namespace obscura::test
