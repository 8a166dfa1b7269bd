// The host of the delegate tests: the in-memory host whose logged errors are checked when it goes
// away, after the delegate is destroyed (so what destruction logs counts too). A test declares each
// error it provokes with expectError; an undeclared error, or a declared one that never came,
// fails it.
#pragma once

#include "tests/support/expected_errors.h"
#include "tests/support/in_memory_host.h"

#include <string>

namespace obscura::test {

class TestHost : public InMemoryHost {
public:
    using InMemoryHost::InMemoryHost;
    ~TestHost();

    // A logged error containing `fragment` is one this test provokes.
    void expectError(std::string fragment) { expected_.add(std::move(fragment)); }

private:
    ExpectedErrors expected_;
};

}  // namespace obscura::test
