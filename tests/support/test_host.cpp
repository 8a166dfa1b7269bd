#include "tests/support/test_host.h"

#include <gtest/gtest.h>

namespace obscura::test {

TestHost::~TestHost() {
    if (delegate()) EXPECT_EQ(destroyDelegate(), OBSCURA_OK) << lastError();
    expected_.check(loggedErrors(), "the plugin");
}

}  // namespace obscura::test
