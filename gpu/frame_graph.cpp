#include "gpu/frame_graph.h"

#include "gpu/timestamps.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace obscura::gpu {
namespace {

struct UsageState {
    VkImageLayout layout;
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageUsageFlags imageUsage;
    VkBufferUsageFlags bufferUsage;
};

UsageState stateOf(Usage u, bool depthFormat) {
    switch (u) {
        case Usage::ColorAttachment:
            return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT,
                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0};
        case Usage::DepthStencilAttachment:
            return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, 0};
        case Usage::SampledCompute:
            return {depthFormat ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                    VK_IMAGE_USAGE_SAMPLED_BIT, 0};
        case Usage::SampledFragment:
            return {depthFormat ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                    VK_IMAGE_USAGE_SAMPLED_BIT, 0};
        case Usage::StorageImageRead:
            return {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                    VK_IMAGE_USAGE_STORAGE_BIT, 0};
        case Usage::StorageImageWrite:
            return {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_IMAGE_USAGE_STORAGE_BIT, 0};
        case Usage::StorageBufferRead:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                    0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};
        case Usage::StorageBufferReadFragment:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT, 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};
        case Usage::StorageBufferWrite:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};
        case Usage::TransferSrc:
            return {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_BUFFER_USAGE_TRANSFER_SRC_BIT};
        case Usage::TransferDst:
            return {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    }
    throw std::logic_error("unknown usage");
}

constexpr VkAccessFlags2 kWriteAccesses = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;

}  // namespace

bool isWrite(Usage u) {
    return u == Usage::ColorAttachment || u == Usage::DepthStencilAttachment || u == Usage::StorageImageWrite ||
           u == Usage::StorageBufferWrite || u == Usage::TransferDst;
}

// ---------------------------------------------------------------------------------------------
ImagePtr TransientImagePool::acquire(const ImageDesc& desc, const std::string& name) {
    for (auto& e : entries_) {
        if (!e.usedThisFrame && e.image->desc == desc) {
            e.usedThisFrame = true;
            return e.image;
        }
    }
    entries_.push_back({device_.createImage(desc, name.c_str()), true});
    return entries_.back().image;
}

void TransientImagePool::endFrame() {
    std::erase_if(entries_, [](const Entry& e) { return !e.usedThisFrame; });
    for (auto& e : entries_) e.usedThisFrame = false;
}

// ---------------------------------------------------------------------------------------------
VkImage PassResources::image(ImageHandle h) const { return graph_.images_.at(h.index).image->image; }
VkImageView PassResources::view(ImageHandle h) const { return graph_.images_.at(h.index).image->view; }
VkImageView PassResources::stencilView(ImageHandle h) const { return graph_.images_.at(h.index).image->stencilView; }
VkImageView PassResources::levelView(ImageHandle h, uint32_t level) const {
    return graph_.images_.at(h.index).image->levelViews.at(level);
}
const ImageDesc& PassResources::desc(ImageHandle h) const { return graph_.images_.at(h.index).desc; }
VkBuffer PassResources::buffer(BufferHandle h) const { return graph_.buffers_.at(h.index).buffer->buffer; }
VkDeviceSize PassResources::bufferSize(BufferHandle h) const { return graph_.buffers_.at(h.index).buffer->size; }

// ---------------------------------------------------------------------------------------------
ImageHandle FrameGraph::PassBuilder::read(ImageHandle h, Usage usage) {
    graph_.passes_[pass_].accesses.push_back({h.index, true, usage});
    return h;
}
ImageHandle FrameGraph::PassBuilder::write(ImageHandle h, Usage usage) {
    graph_.passes_[pass_].accesses.push_back({h.index, true, usage});
    return h;
}
BufferHandle FrameGraph::PassBuilder::read(BufferHandle h, Usage usage) {
    graph_.passes_[pass_].accesses.push_back({h.index, false, usage});
    return h;
}
BufferHandle FrameGraph::PassBuilder::write(BufferHandle h, Usage usage) {
    graph_.passes_[pass_].accesses.push_back({h.index, false, usage});
    return h;
}
ImageHandle FrameGraph::PassBuilder::colorAttachment(ImageHandle h, std::optional<VkClearColorValue> clear) {
    write(h, Usage::ColorAttachment);
    Attachment a;
    a.image = h;
    if (clear) {
        a.load = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.clear.color = *clear;
    }
    graph_.passes_[pass_].attachments.push_back(a);
    return h;
}
ImageHandle FrameGraph::PassBuilder::depthStencilAttachment(ImageHandle h,
                                                           std::optional<VkClearDepthStencilValue> clear) {
    write(h, Usage::DepthStencilAttachment);
    Attachment a;
    a.image = h;
    a.depth = true;
    if (clear) {
        a.load = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.clear.depthStencil = *clear;
    }
    graph_.passes_[pass_].attachments.push_back(a);
    return h;
}

ImageHandle FrameGraph::createImage(const std::string& name, const ImageDesc& desc) {
    images_.push_back({name, desc, nullptr, true, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED, false});
    return {static_cast<uint32_t>(images_.size() - 1)};
}

ImageHandle FrameGraph::importImage(const std::string& name, ImagePtr image, VkImageLayout currentLayout) {
    ImageDesc desc = image->desc;
    images_.push_back({name, desc, std::move(image), false, currentLayout, currentLayout, false});
    return {static_cast<uint32_t>(images_.size() - 1)};
}

BufferHandle FrameGraph::importBuffer(const std::string& name, BufferPtr buffer) {
    buffers_.push_back({name, std::move(buffer), false});
    return {static_cast<uint32_t>(buffers_.size() - 1)};
}

void FrameGraph::addPass(const std::string& name, PassKind kind, const std::function<void(PassBuilder&)>& setup,
                         RecordFn record) {
    passes_.push_back({name, kind, {}, {}, std::move(record)});
    PassBuilder builder(*this, static_cast<uint32_t>(passes_.size() - 1));
    setup(builder);
}

void FrameGraph::markOutput(ImageHandle h) { images_.at(h.index).output = true; }
void FrameGraph::markOutput(BufferHandle h) { buffers_.at(h.index).output = true; }

VkImageLayout FrameGraph::finalLayout(ImageHandle h) const { return images_.at(h.index).finalLayout; }

void FrameGraph::compile() {
    compiled_.clear();
    const size_t n = passes_.size();

    // Culling, walking backwards from the outputs: a pass lives if it writes something needed.
    std::set<std::pair<bool, uint32_t>> needed;
    for (uint32_t i = 0; i < images_.size(); ++i)
        if (images_[i].output) needed.insert({true, i});
    for (uint32_t i = 0; i < buffers_.size(); ++i)
        if (buffers_[i].output) needed.insert({false, i});
    std::vector<bool> alive(n, false);
    for (size_t p = n; p-- > 0;) {
        for (const auto& a : passes_[p].accesses)
            if (isWrite(a.usage) && needed.count({a.isImage, a.resource})) alive[p] = true;
        if (!alive[p]) continue;
        for (const auto& a : passes_[p].accesses)
            if (!isWrite(a.usage) || a.usage == Usage::ColorAttachment || a.usage == Usage::DepthStencilAttachment)
                needed.insert({a.isImage, a.resource});
    }

    // Derive usage flags of transient images from every live declaration.
    for (size_t p = 0; p < n; ++p) {
        if (!alive[p]) continue;
        for (const auto& a : passes_[p].accesses)
            if (a.isImage && images_[a.resource].transient)
                images_[a.resource].desc.usage |= stateOf(a.usage, isDepthFormat(images_[a.resource].desc.format)).imageUsage;
    }

    // Barrier planning: track the last layout, the last write and the reads since then.
    struct Track {
        VkImageLayout layout;
        VkPipelineStageFlags2 writeStage = 0;
        VkAccessFlags2 writeAccess = 0;
        VkPipelineStageFlags2 readStages = 0;
        bool written = false;
    };
    std::vector<Track> imageTrack(images_.size()), bufferTrack(buffers_.size());
    for (size_t i = 0; i < images_.size(); ++i) {
        imageTrack[i].layout = images_[i].initialLayout;
        imageTrack[i].written = !images_[i].transient;
        if (!images_[i].transient) {
            // Imported images were last touched by an earlier submission that the host waited for.
            imageTrack[i].writeStage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
            imageTrack[i].writeAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
        }
    }
    for (auto& t : bufferTrack) t.written = true;

    // Last live pass touching each image: attachments not read after it need not be stored.
    std::vector<int> lastUse(images_.size(), -1);
    for (size_t p = 0; p < n; ++p)
        if (alive[p])
            for (const auto& a : passes_[p].accesses)
                if (a.isImage) lastUse[a.resource] = static_cast<int>(p);

    for (size_t p = 0; p < n; ++p) {
        CompiledPass cp{passes_[p].name, passes_[p].kind, !alive[p], {}, passes_[p].attachments};
        if (alive[p]) {
            for (const auto& a : passes_[p].accesses) {
                bool depth = a.isImage && isDepthFormat(images_[a.resource].desc.format);
                UsageState s = stateOf(a.usage, depth);
                Track& t = a.isImage ? imageTrack[a.resource] : bufferTrack[a.resource];
                if (!isWrite(a.usage) && !t.written)
                    throw std::logic_error("frame graph: pass '" + passes_[p].name + "' reads '" +
                                           (a.isImage ? images_[a.resource].name : buffers_[a.resource].name) +
                                           "' before anything wrote it");
                bool layoutChange = a.isImage && t.layout != s.layout;
                bool afterWrite = t.writeAccess != 0;
                bool writeAfterRead = isWrite(a.usage) && t.readStages != 0;
                // Two accesses in one pass with the same layout need no barrier between them.
                bool samePass = false;
                for (const auto& b : cp.barriers)
                    if (b.resource == a.resource && b.isImage == a.isImage) samePass = true;
                if ((layoutChange || afterWrite || writeAfterRead) && !samePass) {
                    PlannedBarrier b{a.resource,
                                     a.isImage,
                                     t.layout,
                                     a.isImage ? s.layout : VK_IMAGE_LAYOUT_UNDEFINED,
                                     t.writeStage | t.readStages,
                                     t.writeAccess,
                                     s.stage,
                                     s.access};
                    if (b.srcStage == 0) b.srcStage = VK_PIPELINE_STAGE_2_NONE;
                    cp.barriers.push_back(b);
                    t.readStages = 0;
                    t.writeStage = 0;
                    t.writeAccess = 0;
                } else if (samePass) {
                    for (auto& b : cp.barriers)
                        if (b.resource == a.resource && b.isImage == a.isImage) {
                            b.dstStage |= s.stage;
                            b.dstAccess |= s.access;
                        }
                }
                if (a.isImage) t.layout = s.layout;
                if (isWrite(a.usage)) {
                    t.written = true;
                    t.writeStage |= s.stage;
                    t.writeAccess |= s.access & kWriteAccesses;
                } else {
                    t.readStages |= s.stage;
                }
            }
            for (auto& att : cp.attachments) {
                const auto& img = images_[att.image.index];
                if (lastUse[att.image.index] == static_cast<int>(p) && !img.output && img.transient)
                    att.store = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            }
        }
        compiled_.push_back(std::move(cp));
    }
    for (size_t i = 0; i < images_.size(); ++i) images_[i].finalLayout = imageTrack[i].layout;
}

void FrameGraph::execute(TransientImagePool& pool, PipelineCache& pipelines, VkCommandBuffer cmd,
                         Timestamps* timestamps) {
    for (auto& img : images_)
        if (img.transient && !img.image && img.desc.usage != 0) img.image = pool.acquire(img.desc, img.name);

    PassResources resources(*this, pool.device(), pipelines);
    for (size_t p = 0; p < passes_.size(); ++p) {
        const CompiledPass& cp = compiled_[p];
        if (cp.culled) continue;
        if (timestamps) timestamps->begin(cmd, cp.name);

        std::vector<VkImageMemoryBarrier2> imageBarriers;
        std::vector<VkBufferMemoryBarrier2> bufferBarriers;
        for (const auto& b : cp.barriers) {
            if (b.isImage) {
                const auto& img = images_[b.resource];
                VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
                ib.srcStageMask = b.srcStage;
                ib.srcAccessMask = b.srcAccess;
                ib.dstStageMask = b.dstStage;
                ib.dstAccessMask = b.dstAccess;
                ib.oldLayout = b.oldLayout;
                ib.newLayout = b.newLayout;
                ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                ib.image = img.image->image;
                ib.subresourceRange = {aspectsOf(img.desc.format), 0, VK_REMAINING_MIP_LEVELS, 0, 1};
                imageBarriers.push_back(ib);
            } else {
                VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
                bb.srcStageMask = b.srcStage;
                bb.srcAccessMask = b.srcAccess;
                bb.dstStageMask = b.dstStage;
                bb.dstAccessMask = b.dstAccess;
                bb.srcQueueFamilyIndex = bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                bb.buffer = buffers_[b.resource].buffer->buffer;
                bb.size = VK_WHOLE_SIZE;
                bufferBarriers.push_back(bb);
            }
        }
        if (!imageBarriers.empty() || !bufferBarriers.empty()) {
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.imageMemoryBarrierCount = static_cast<uint32_t>(imageBarriers.size());
            dep.pImageMemoryBarriers = imageBarriers.data();
            dep.bufferMemoryBarrierCount = static_cast<uint32_t>(bufferBarriers.size());
            dep.pBufferMemoryBarriers = bufferBarriers.data();
            vkCmdPipelineBarrier2(cmd, &dep);
        }

        if (cp.kind == PassKind::Raster) {
            std::vector<VkRenderingAttachmentInfo> colors;
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            bool hasDepth = false, stencil = false;
            VkExtent2D extent{0, 0};
            for (const auto& att : cp.attachments) {
                const auto& img = images_[att.image.index];
                extent = {img.desc.width, img.desc.height};
                VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                info.imageView = img.image->view;
                info.loadOp = att.load;
                info.storeOp = att.store;
                info.clearValue = att.clear;
                if (att.depth) {
                    info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
                    depth = info;
                    hasDepth = true;
                    stencil = hasStencil(img.desc.format);
                } else {
                    info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                    colors.push_back(info);
                }
            }
            VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
            ri.renderArea = {{0, 0}, extent};
            ri.layerCount = 1;
            ri.colorAttachmentCount = static_cast<uint32_t>(colors.size());
            ri.pColorAttachments = colors.data();
            ri.pDepthAttachment = hasDepth ? &depth : nullptr;
            ri.pStencilAttachment = stencil ? &depth : nullptr;
            vkCmdBeginRendering(cmd, &ri);
            VkViewport vp{0, 0, float(extent.width), float(extent.height), 0.0f, 1.0f};
            VkRect2D scissor{{0, 0}, extent};
            vkCmdSetViewport(cmd, 0, 1, &vp);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            passes_[p].record(cmd, resources);
            vkCmdEndRendering(cmd);
        } else {
            passes_[p].record(cmd, resources);
        }
        if (timestamps) timestamps->end(cmd);
    }
    // Buffers the host reads after the fence: make the device's writes visible to the host.
    std::vector<VkBufferMemoryBarrier2> hostReads;
    for (const auto& b : buffers_) {
        if (!b.output) continue;
        VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
        bb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        bb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
        bb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        bb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        bb.srcQueueFamilyIndex = bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        bb.buffer = b.buffer->buffer;
        bb.size = VK_WHOLE_SIZE;
        hostReads.push_back(bb);
    }
    if (!hostReads.empty()) {
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.bufferMemoryBarrierCount = static_cast<uint32_t>(hostReads.size());
        dep.pBufferMemoryBarriers = hostReads.data();
        vkCmdPipelineBarrier2(cmd, &dep);
    }
}

}  // namespace obscura::gpu
