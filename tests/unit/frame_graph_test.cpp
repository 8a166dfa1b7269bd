// The frame graph's compile step without a GPU: culling, versions, barriers, load/store ops,
// transient memory, and persistent images from frame to frame (against a mock backend).
#include "gpu/frame_graph.h"
#include "gpu/history_images.h"
#include "tests/unit/mock_frame_backend.h"

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
    g.addPass("writesA", PassKind::Compute, [&](auto& p) { a = p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("writesB", PassKind::Compute, [&](auto& p) { b = p.write(b, Usage::StorageImageWrite); }, {});
    g.markOutput(a);
    g.compile();
    EXPECT_FALSE(g.compiled()[0].culled);
    EXPECT_TRUE(g.compiled()[1].culled);
}

TEST(FrameGraph, KeepsProducersOfWhatOutputsRead) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    g.addPass("produce", PassKind::Compute, [&](auto& p) { a = p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("consume", PassKind::Compute, [&](auto& p) {
        p.read(a, Usage::SampledCompute);
        b = p.write(b, Usage::StorageImageWrite);
    }, {});
    g.markOutput(b);
    g.compile();
    EXPECT_FALSE(g.compiled()[0].culled);
    EXPECT_FALSE(g.compiled()[1].culled);
}

TEST(FrameGraph, DerivesLayoutTransitionsAndHazards) {
    FrameGraph g;
    ImageHandle color = g.createImage("color", colorDesc()), out = g.createImage("out", colorDesc());
    g.addPass("raster", PassKind::Raster, [&](auto& p) { color = p.colorAttachment(color, VkClearColorValue{}); }, {});
    g.addPass("post", PassKind::Compute, [&](auto& p) {
        p.read(color, Usage::SampledCompute);
        out = p.write(out, Usage::StorageImageWrite);
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
        depth = p.depthStencilAttachment(depth, VkClearDepthStencilValue{1.0f, 0});
        color = p.colorAttachment(color, VkClearColorValue{});
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
        b = p.write(b, Usage::StorageImageWrite);
    }, {});
    g.markOutput(b);
    EXPECT_THROW(g.compile(), std::logic_error);
}

TEST(FrameGraph, WriteAfterReadWaitsForTheReader) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    g.addPass("w1", PassKind::Compute, [&](auto& p) { a = p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("r", PassKind::Compute, [&](auto& p) {
        p.read(a, Usage::StorageImageRead);
        b = p.write(b, Usage::StorageImageWrite);
    }, {});
    g.addPass("w2", PassKind::Compute, [&](auto& p) {
        p.read(b, Usage::StorageImageRead);
        a = p.write(a, Usage::StorageImageWrite);
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

// Filament's rule: a write makes a new version, and what read the old one before may not read it
// after.
TEST(FrameGraph, EachWriteMakesANewVersion) {
    FrameGraph g;
    ImageHandle v0 = g.createImage("a", colorDesc());
    ImageHandle v1, v2;
    g.addPass("first", PassKind::Compute, [&](auto& p) { v1 = p.write(v0, Usage::StorageImageWrite); }, {});
    g.addPass("second", PassKind::Compute, [&](auto& p) {
        p.read(v1, Usage::StorageImageRead);
        v2 = p.write(v1, Usage::StorageImageWrite);
    }, {});
    EXPECT_EQ(v0.index, v1.index);
    EXPECT_EQ(v1.version, v0.version + 1);
    EXPECT_EQ(v2.version, v1.version + 1);
}

TEST(FrameGraph, ReadingAnOldVersionAfterANewerWriteIsAnError) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), out = g.createImage("out", colorDesc());
    ImageHandle first, second;
    g.addPass("first", PassKind::Compute, [&](auto& p) { first = p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("second", PassKind::Compute, [&](auto& p) { second = p.write(first, Usage::StorageImageWrite); }, {});
    g.addPass("stale", PassKind::Compute, [&](auto& p) {
        p.read(first, Usage::SampledCompute);
        out = p.write(out, Usage::StorageImageWrite);
    }, {});
    g.markOutput(out);
    g.markOutput(second);
    EXPECT_THROW(g.compile(), std::logic_error);
}

TEST(FrameGraph, WritingOverAnOldVersionIsAnError) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc());
    ImageHandle first, again;
    g.addPass("first", PassKind::Compute, [&](auto& p) { first = p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("second", PassKind::Compute, [&](auto& p) { (void)p.write(first, Usage::StorageImageWrite); }, {});
    g.addPass("stale", PassKind::Compute, [&](auto& p) { again = p.write(first, Usage::StorageImageWrite); }, {});
    g.markOutput(again);
    EXPECT_THROW(g.compile(), std::logic_error);
}

// An attachment that keeps its contents reads the version before it: the pass that wrote that
// version is kept with it.
TEST(FrameGraph, LoadedAttachmentsKeepTheirWriter) {
    FrameGraph g;
    ImageHandle color = g.createImage("color", colorDesc());
    g.addPass("clear", PassKind::Raster, [&](auto& p) { color = p.colorAttachment(color, VkClearColorValue{}); }, {});
    g.addPass("overdraw", PassKind::Raster, [&](auto& p) { color = p.colorAttachment(color); }, {});
    g.markOutput(color);
    g.compile();
    EXPECT_FALSE(g.compiled()[0].culled);
    EXPECT_FALSE(g.compiled()[1].culled);
    EXPECT_EQ(g.compiled()[1].attachments[0].load, VK_ATTACHMENT_LOAD_OP_LOAD);
}

TEST(FrameGraph, TexturesAreReadWithoutABarrierAndNeverWritten) {
    auto texture = std::make_shared<Image>();
    texture->desc = colorDesc();
    texture->desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    texture->layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    FrameGraph g;
    ImageHandle t = g.importTexture("texture", texture), out = g.createImage("out", colorDesc());
    g.addPass("read", PassKind::Compute, [&](auto& p) {
        p.read(t, Usage::SampledCompute);
        out = p.write(out, Usage::StorageImageWrite);
    }, {});
    g.markOutput(out);
    g.compile();
    for (const auto& b : g.compiled()[0].barriers) EXPECT_FALSE(b.isImage && b.resource == t.index);

    FrameGraph writes;
    ImageHandle w = writes.importTexture("texture", texture);
    writes.addPass("write", PassKind::Compute, [&](auto& p) { (void)p.write(w, Usage::StorageImageWrite); }, {});
    EXPECT_THROW(writes.compile(), std::logic_error);
}

// Three images in a chain, each read by the next pass only: the first and the last are never
// alive together and share memory; the last one's first use waits for the first one's last.
TEST(FrameGraph, TransientsWhoseLifetimesDoNotOverlapShareMemory) {
    FrameGraph g;
    ImageHandle a = g.createImage("a", colorDesc()), b = g.createImage("b", colorDesc());
    ImageHandle c = g.createImage("c", colorDesc()), out = g.createImage("out", colorDesc());
    g.addPass("writeA", PassKind::Compute, [&](auto& p) { a = p.write(a, Usage::StorageImageWrite); }, {});
    g.addPass("aToB", PassKind::Compute, [&](auto& p) {
        p.read(a, Usage::SampledCompute);
        b = p.write(b, Usage::StorageImageWrite);
    }, {});
    g.addPass("bToC", PassKind::Compute, [&](auto& p) {
        p.read(b, Usage::SampledCompute);
        c = p.write(c, Usage::StorageImageWrite);
    }, {});
    g.addPass("cToOut", PassKind::Compute, [&](auto& p) {
        p.read(c, Usage::SampledCompute);
        out = p.write(out, Usage::StorageImageWrite);
    }, {});
    g.markOutput(out);
    g.compile();
    const TransientMemory& memory = g.transientMemory();
    ASSERT_EQ(memory.placements.size(), 4u);
    auto placement = [&](ImageHandle h) {
        for (const auto& p : memory.placements)
            if (p.image == h.index) return p;
        ADD_FAILURE() << "no placement for image " << h.index;
        return TransientMemory::Placement{};
    };
    // Alive together: a with b, b with c, c with out.
    EXPECT_NE(placement(a).offset, placement(b).offset);
    EXPECT_NE(placement(b).offset, placement(c).offset);
    EXPECT_NE(placement(c).offset, placement(out).offset);
    // Two images' memory holds all four.
    const VkDeviceSize one = placement(a).size;
    EXPECT_EQ(memory.bytes(), 2 * one);
    EXPECT_EQ(memory.unaliasedBytes(), 4 * one);
    // c lies over a (or b over out's place, and so on): its first use waits for what was there.
    for (ImageHandle later : {c, out}) {
        bool waits = false;
        for (const auto& pass : g.compiled())
            for (const auto& bar : pass.barriers)
                if (bar.isImage && bar.resource == later.index && bar.oldLayout == VK_IMAGE_LAYOUT_UNDEFINED)
                    waits = (bar.srcStage & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT) != 0;
        EXPECT_TRUE(waits) << g.imageName(later.index);
    }
}

// Granite's history input: the first frame has no history, the next reads what the first wrote,
// in the layout the first left it in, and a resize starts afresh.
TEST(FrameGraph, HistoriesCarryFromFrameToFrame) {
    test::MockFrameBackend backend;
    HistoryImages history;
    ImageDesc desc = colorDesc();
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    auto frame = [&](const ImageDesc& d) {
        FrameGraph g;
        FrameGraph::History h = g.addHistory("history", history, d);
        g.addPass("temporal", PassKind::Compute, [&](auto& p) {
            p.read(h.previous, Usage::SampledCompute);
            (void)p.write(h.current, Usage::StorageImageWrite);
        }, {});
        backend.run(g);
        return h.previousEmpty;
    };
    EXPECT_TRUE(frame(desc));
    EXPECT_FALSE(frame(desc));
    // The second frame read the image the first wrote, left in GENERAL: no layout carried by hand.
    const auto& second = backend.frames[1];
    bool readFromGeneral = false;
    for (const auto& b : second.passes[0].barriers)
        if (second.imageNames[b.resource] == "history.previous")
            readFromGeneral = b.oldLayout == VK_IMAGE_LAYOUT_GENERAL &&
                              b.newLayout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    EXPECT_TRUE(readFromGeneral);
    // Passes writing images that outlive the frame are kept though nothing reads them now.
    EXPECT_FALSE(second.passes[0].culled);
    ImageDesc resized = desc;
    resized.width = 32;
    EXPECT_TRUE(frame(resized));
}

}  // namespace
}  // namespace obscura::gpu
