// The frame graph's compile step without a GPU: culling, barriers and load/store ops.
#include "gpu/frame_graph.h"

#include <gtest/gtest.h>

namespace obscura::gpu {
namespace {

ImageDesc colorDesc() {
    ImageDesc d;
    d.format = VK_FORMAT_R8G8B8A8_UNORM;
    d.width = d.height = 16;
    return d;
}

TEST(FrameGraph, CullsPassesNobodyReads) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    g.addPass("writesA", PassKind::Compute, [&](auto& p) { p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("writesB", PassKind::Compute, [&](auto& p) { p.write(b, Usage::StorageImageWrite); }, {});
    g.markOutput(a);
    g.compile();
    EXPECT_FALSE(g.compiled()[0].culled);
    EXPECT_TRUE(g.compiled()[1].culled);
}

TEST(FrameGraph, KeepsProducersOfWhatOutputsRead) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    g.addPass("produce", PassKind::Compute, [&](auto& p) { p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("consume", PassKind::Compute, [&](auto& p) {
        p.read(a, Usage::SampledCompute);
        p.write(b, Usage::StorageImageWrite);
    }, {});
    g.markOutput(b);
    g.compile();
    EXPECT_FALSE(g.compiled()[0].culled);
    EXPECT_FALSE(g.compiled()[1].culled);
}

TEST(FrameGraph, DerivesLayoutTransitionsAndHazards) {
    FrameGraph g;
    ImageHandle color = g.createImage("color", colorDesc()), out = g.createImage("out", colorDesc());
    g.addPass("raster", PassKind::Raster, [&](auto& p) { p.colorAttachment(color, VkClearColorValue{}); }, {});
    g.addPass("post", PassKind::Compute, [&](auto& p) {
        p.read(color, Usage::SampledCompute);
        p.write(out, Usage::StorageImageWrite);
    }, {});
    g.markOutput(out);
    g.compile();
    const auto& raster = g.compiled()[0];
    ASSERT_EQ(raster.barriers.size(), 1u);
    EXPECT_EQ(raster.barriers[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(raster.barriers[0].newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    const auto& post = g.compiled()[1];
    ASSERT_EQ(post.barriers.size(), 2u);
    const PlannedBarrier& read = post.barriers[0];
    EXPECT_EQ(read.oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(read.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_TRUE(read.srcAccess & VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    EXPECT_TRUE(read.dstStage & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(post.barriers[1].newLayout, VK_IMAGE_LAYOUT_GENERAL);
    // Usage flags come from the declarations.
    EXPECT_TRUE(g.imageDesc(color).usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    EXPECT_TRUE(g.imageDesc(color).usage & VK_IMAGE_USAGE_SAMPLED_BIT);
}

TEST(FrameGraph, AttachmentsNobodyReadsLaterAreNotStored) {
    FrameGraph g;
    ImageHandle depth = g.createImage("depth", [] {
        ImageDesc d;
        d.format = VK_FORMAT_D32_SFLOAT;
        d.width = d.height = 16;
        return d;
    }());
    ImageHandle color = g.createImage("color", colorDesc());
    g.addPass("raster", PassKind::Raster, [&](auto& p) {
        p.depthStencilAttachment(depth, VkClearDepthStencilValue{1.0f, 0});
        p.colorAttachment(color, VkClearColorValue{});
    }, {});
    g.markOutput(color);
    g.compile();
    const auto& atts = g.compiled()[0].attachments;
    ASSERT_EQ(atts.size(), 2u);
    EXPECT_EQ(atts[0].load, VK_ATTACHMENT_LOAD_OP_CLEAR);
    EXPECT_EQ(atts[0].store, VK_ATTACHMENT_STORE_OP_DONT_CARE);
    EXPECT_EQ(atts[1].store, VK_ATTACHMENT_STORE_OP_STORE);
}

TEST(FrameGraph, ReadBeforeWriteIsAnError) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    g.addPass("reader", PassKind::Compute, [&](auto& p) {
        p.read(a, Usage::SampledCompute);
        p.write(b, Usage::StorageImageWrite);
    }, {});
    g.markOutput(b);
    EXPECT_THROW(g.compile(), std::logic_error);
}

TEST(FrameGraph, WriteAfterReadWaitsForTheReader) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    g.addPass("w1", PassKind::Compute, [&](auto& p) { p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("r", PassKind::Compute, [&](auto& p) {
        p.read(a, Usage::StorageImageRead);
        p.write(b, Usage::StorageImageWrite);
    }, {});
    g.addPass("w2", PassKind::Compute, [&](auto& p) {
        p.read(b, Usage::StorageImageRead);
        p.write(a, Usage::StorageImageWrite);
    }, {});
    g.markOutput(a);
    g.compile();
    bool found = false;
    for (const auto& bar : g.compiled()[2].barriers)
        if (bar.resource == a.index) {
            found = true;
            EXPECT_TRUE(bar.srcStage & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace obscura::gpu
