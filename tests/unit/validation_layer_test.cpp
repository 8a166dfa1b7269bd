// A planted validation error must be seen: the messenger counts it, and the delegate turns a
// nonzero count into OBSCURA_ERROR_VALIDATION (see render_delegate.cpp), failing the caller.
#include "gpu/context.h"

#include <gtest/gtest.h>

namespace obscura::gpu {
namespace {

TEST(ValidationLayer, PlantedErrorIsCounted) {
    std::vector<std::string> errors;
    ContextOptions options;
    options.validation = true;
    options.log = [&](LogLevel level, const std::string& message) {
        if (level == LogLevel::Error) errors.push_back(message);
    };
    auto context = Context::create(options);
    ASSERT_TRUE(context.ok()) << context.error();
    ASSERT_EQ((*context)->validationErrorCount(), 0u);
    // A zero-sized buffer is invalid usage (VUID-VkBufferCreateInfo-size-00912).
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = 0;
    bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer((*context)->device(), &bi, nullptr, &buffer) == VK_SUCCESS && buffer)
        vkDestroyBuffer((*context)->device(), buffer, nullptr);
    EXPECT_GE((*context)->validationErrorCount(), 1u);
    ASSERT_FALSE(errors.empty());
    EXPECT_NE(errors.front().find("size"), std::string::npos) << errors.front();
}

}  // namespace
}  // namespace obscura::gpu
