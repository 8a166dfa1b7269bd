// A fixture for tests of gpu/ on their own: a Device with the validation layer on, and a test
// that leaves any validation error behind fails.
#pragma once

#include "gpu/device.h"

#include <gtest/gtest.h>

#include <memory>

namespace obscura::gpu {

class ValidatedDeviceTest : public ::testing::Test {
protected:
    void SetUp() override {
        ContextOptions options;
        options.validation = true;
        auto context = Context::create(options);
        ASSERT_TRUE(context.ok()) << context.error();
        device_ = std::make_unique<Device>(std::move(*context));
    }
    void TearDown() override {
        if (device_) EXPECT_EQ(device_->context().validationErrorCount(), 0u);
    }

    std::unique_ptr<Device> device_;
};

}  // namespace obscura::gpu
