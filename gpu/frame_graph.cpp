#include "gpu/frame_graph.h"

#include "gpu/frame_backend.h"
#include "gpu/memory.h"
#include "gpu/history_images.h"
#include "gpu/timestamps.h"
#include "gpu/vulkan_functions.h"

#include <algorithm>
#include <cstring>
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
        case Usage::StorageBufferReadGraphics:
            return {VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT, 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};
        case Usage::StorageBufferWrite:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};
        case Usage::IndirectCommandRead:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                    VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, 0, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT};
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

VkAttachmentLoadOp loadOp(FrameGraph::PassBuilder::Load load) {
    return load == FrameGraph::PassBuilder::Load::Keep ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
}

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

// Without a device to ask: the texels' bytes (every mip), 256-byte aligned, any memory type.
VkMemoryRequirements estimateImageMemory(const ImageDesc& desc) {
    VkDeviceSize texel = 4;
    switch (desc.format) {
        case VK_FORMAT_R8_UNORM: texel = 1; break;
        case VK_FORMAT_R8G8_UNORM: texel = 2; break;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT: texel = 8; break;
        case VK_FORMAT_R32G32B32A32_SFLOAT: texel = 16; break;
        default: break;
    }
    VkDeviceSize bytes = 0;
    for (uint32_t level = 0; level < desc.mipLevels; ++level)
        bytes += VkDeviceSize(std::max(desc.width >> level, 1u)) * std::max(desc.height >> level, 1u) * desc.depth *
                 texel * desc.samples;
    return {alignUp(bytes, 256), 256, ~0u};
}

}  // namespace

bool isWrite(Usage u) {
    return u == Usage::ColorAttachment || u == Usage::DepthStencilAttachment || u == Usage::StorageImageWrite ||
           u == Usage::StorageBufferWrite || u == Usage::TransferDst;
}

VkDeviceSize TransientMemory::bytes() const {
    VkDeviceSize total = 0;
    for (const Heap& heap : heaps) total += heap.size;
    return total;
}

VkDeviceSize TransientMemory::unaliasedBytes() const {
    VkDeviceSize total = 0;
    for (const Placement& p : placements) total += p.size;
    return total;
}

// ---------------------------------------------------------------------------------------------
VkImage PassResources::image(ImageHandle h) const { return graph_.images_.at(h.index).image->image; }
VkImageView PassResources::view(ImageHandle h) const { return graph_.images_.at(h.index).image->view; }
VkImageView PassResources::stencilView(ImageHandle h) const { return graph_.images_.at(h.index).image->stencilView; }
VkImageView PassResources::storageView(ImageHandle h) const {
    const Image& image = *graph_.images_.at(h.index).image;
    return image.storageView ? image.storageView : image.view;
}
VkImageView PassResources::levelView(ImageHandle h, uint32_t level) const {
    return graph_.images_.at(h.index).image->levelViews.at(level);
}
const ImageDesc& PassResources::desc(ImageHandle h) const { return graph_.images_.at(h.index).desc; }
VkBuffer PassResources::buffer(BufferHandle h) const { return graph_.buffers_.at(h.index).buffer->buffer; }
VkDeviceSize PassResources::bufferSize(BufferHandle h) const { return graph_.buffers_.at(h.index).buffer->size; }

// ---------------------------------------------------------------------------------------------
void FrameGraph::PassBuilder::read(ImageHandle h, Usage usage) {
    if (isWrite(usage)) throw std::logic_error("frame graph: a read with a write usage");
    graph_.passes_[pass_].accesses.push_back({h.index, true, usage, h.version, false});
}
void FrameGraph::PassBuilder::read(BufferHandle h, Usage usage) {
    if (isWrite(usage)) throw std::logic_error("frame graph: a read with a write usage");
    graph_.passes_[pass_].accesses.push_back({h.index, false, usage, h.version, false});
}
ImageHandle FrameGraph::PassBuilder::write(ImageHandle h, Usage usage) {
    return {h.index, graph_.writeVersion(pass_, h.index, true, h.version, usage)};
}
BufferHandle FrameGraph::PassBuilder::write(BufferHandle h, Usage usage) {
    return {h.index, graph_.writeVersion(pass_, h.index, false, h.version, usage)};
}

ImageHandle FrameGraph::PassBuilder::attachment(ImageHandle h, bool depth, VkAttachmentLoadOp load,
                                               VkClearValue clear) {
    Attachment a;
    a.image = write(h, depth ? Usage::DepthStencilAttachment : Usage::ColorAttachment);
    a.depth = depth;
    a.load = load;
    a.clear = clear;
    graph_.passes_[pass_].accesses.back().readsPrevious = load == VK_ATTACHMENT_LOAD_OP_LOAD;
    graph_.passes_[pass_].attachments.push_back(a);
    return a.image;
}

ImageHandle FrameGraph::PassBuilder::colorAttachment(ImageHandle h, Load load) {
    return attachment(h, false, loadOp(load), {});
}
ImageHandle FrameGraph::PassBuilder::colorAttachment(ImageHandle h, VkClearColorValue clear) {
    return attachment(h, false, VK_ATTACHMENT_LOAD_OP_CLEAR, {.color = clear});
}
void FrameGraph::PassBuilder::unusedColorAttachment() { graph_.passes_[pass_].attachments.push_back({}); }
void FrameGraph::PassBuilder::usesPipeline(PipelineCache::Request request) {
    graph_.passes_[pass_].pipelines.push_back(std::move(request));
}
ImageHandle FrameGraph::PassBuilder::depthStencilAttachment(ImageHandle h, Load load) {
    return attachment(h, true, loadOp(load), {});
}
ImageHandle FrameGraph::PassBuilder::depthStencilAttachment(ImageHandle h, VkClearDepthStencilValue clear) {
    return attachment(h, true, VK_ATTACHMENT_LOAD_OP_CLEAR, {.depthStencil = clear});
}

uint32_t FrameGraph::writeVersion(uint32_t pass, uint32_t resource, bool isImage, uint32_t version, Usage usage) {
    if (!isWrite(usage)) throw std::logic_error("frame graph: a write with a read usage");
    uint32_t& versions = isImage ? images_.at(resource).versions : buffers_.at(resource).versions;
    // A second write of the resource in the same pass (another usage, another dispatch) is the
    // same new version, whether it names the version before the pass or the pass's own.
    for (const Access& a : passes_[pass].accesses)
        if (a.resource == resource && a.isImage == isImage && isWrite(a.usage) &&
            (version == a.version || version == a.from)) {
            passes_[pass].accesses.push_back({resource, isImage, usage, a.version, false, a.from});
            return a.version;
        }
    passes_[pass].accesses.push_back({resource, isImage, usage, versions + 1, false, version});
    return ++versions;
}

ImageHandle FrameGraph::addImage(ImageResource resource) {
    images_.push_back(std::move(resource));
    return {static_cast<uint32_t>(images_.size() - 1), 0};
}

ImageHandle FrameGraph::createImage(const std::string& name, const ImageDesc& desc) {
    ImageResource r;
    r.name = name;
    r.desc = desc;
    return addImage(std::move(r));
}

ImageHandle FrameGraph::importTexture(const std::string& name, ImagePtr texture) {
    if (!texture) throw std::logic_error("frame graph: '" + name + "' imports no texture");
    ImageResource r;
    r.name = name;
    r.desc = texture->desc;
    r.residency = Residency::Texture;
    r.initialLayout = texture->layout;
    r.image = std::move(texture);
    return addImage(std::move(r));
}

ImageHandle FrameGraph::importPersistent(const std::string& name, PersistentImage& persistent, const ImageDesc& desc) {
    if (persistent.image_ && !(persistent.image_->desc == desc)) persistent = PersistentImage{};
    ImageResource r;
    r.name = name;
    r.desc = desc;
    r.residency = Residency::Persistent;
    r.persistent = &persistent;
    r.image = persistent.image_;
    r.initialLayout = persistent.image_ ? persistent.image_->layout : VK_IMAGE_LAYOUT_UNDEFINED;
    return addImage(std::move(r));
}

FrameGraph::History FrameGraph::addHistory(const std::string& name, HistoryImages& history, const ImageDesc& desc) {
    const uint32_t previous = history.current_;
    history.current_ = 1 - history.current_;
    History h{importPersistent(name + ".previous", history.images_[previous], desc),
              importPersistent(name, history.images_[history.current_], desc), false};
    h.previousEmpty = !history.images_[previous].holdsContents();
    return h;
}

BufferHandle FrameGraph::importBuffer(const std::string& name, BufferPtr buffer) {
    if (!buffer) throw std::logic_error("frame graph: '" + name + "' imports no buffer");
    BufferResource r;
    r.name = name;
    r.buffer = std::move(buffer);
    buffers_.push_back(std::move(r));
    return {static_cast<uint32_t>(buffers_.size() - 1), 0};
}

BufferHandle FrameGraph::createBuffer(const std::string& name, std::vector<uint8_t> bytes) {
    BufferResource r;
    r.name = name;
    r.bytes = std::move(bytes);
    r.frameBuffer = true;
    buffers_.push_back(std::move(r));
    return {static_cast<uint32_t>(buffers_.size() - 1), 0};
}

void FrameGraph::addPass(const std::string& name, PassKind kind, const std::function<void(PassBuilder&)>& setup,
                         RecordFn record) {
    passes_.push_back({name, kind, {}, {}, std::move(record), {}});
    PassBuilder builder(*this, static_cast<uint32_t>(passes_.size() - 1));
    setup(builder);
}

void FrameGraph::markOutput(ImageHandle h) { images_.at(h.index).output = true; }
void FrameGraph::markOutput(BufferHandle h) { buffers_.at(h.index).output = true; }

void FrameGraph::checkVersions() const {
    std::vector<uint32_t> imageVersion(images_.size(), 0), bufferVersion(buffers_.size(), 0);
    std::vector<int> imageWriter(images_.size(), -1), bufferWriter(buffers_.size(), -1);
    auto nameOf = [&](const Access& a) { return a.isImage ? images_[a.resource].name : buffers_[a.resource].name; };
    for (size_t p = 0; p < passes_.size(); ++p) {
        const Pass& pass = passes_[p];
        for (const Access& a : pass.accesses) {
            const uint32_t current = a.isImage ? imageVersion[a.resource] : bufferVersion[a.resource];
            const int writer = a.isImage ? imageWriter[a.resource] : bufferWriter[a.resource];
            const uint32_t expected = isWrite(a.usage) ? a.from : a.version;
            if (expected != current)
                throw std::logic_error("frame graph: pass '" + pass.name + "' " +
                                       (isWrite(a.usage) ? "writes over" : "reads") + " version " +
                                       std::to_string(expected) + " of '" + nameOf(a) + "', but pass '" +
                                       (writer >= 0 ? passes_[writer].name : std::string("?")) + "' wrote version " +
                                       std::to_string(current));
            const bool transient = a.isImage && images_[a.resource].residency == Residency::Transient;
            if (a.isImage && isWrite(a.usage) && images_[a.resource].residency == Residency::Texture)
                throw std::logic_error("frame graph: pass '" + pass.name + "' writes the texture '" + nameOf(a) + "'");
            if (transient && current == 0 && (!isWrite(a.usage) || a.readsPrevious))
                throw std::logic_error("frame graph: pass '" + pass.name + "' reads '" + nameOf(a) +
                                       "' before anything wrote it");
        }
        for (const Access& a : pass.accesses) {
            if (!isWrite(a.usage)) continue;
            (a.isImage ? imageVersion : bufferVersion)[a.resource] = a.version;
            (a.isImage ? imageWriter : bufferWriter)[a.resource] = int(p);
        }
    }
}

std::vector<bool> FrameGraph::cull() const {
    // Walking backwards from the outputs: a pass lives if it writes a version something needs, or
    // writes an image or buffer from outside the frame (a later frame or the host reads it).
    std::set<std::tuple<bool, uint32_t, uint32_t>> needed;  // (image, resource, version)
    for (uint32_t i = 0; i < images_.size(); ++i)
        if (images_[i].output) needed.insert({true, i, images_[i].versions});
    for (uint32_t i = 0; i < buffers_.size(); ++i)
        if (buffers_[i].output) needed.insert({false, i, buffers_[i].versions});
    std::vector<bool> alive(passes_.size(), false);
    for (size_t p = passes_.size(); p-- > 0;) {
        for (const Access& a : passes_[p].accesses) {
            if (!isWrite(a.usage)) continue;
            const bool outlives = a.isImage ? images_[a.resource].residency != Residency::Transient
                                            : !buffers_[a.resource].frameBuffer;
            if (outlives || needed.count({a.isImage, a.resource, a.version})) alive[p] = true;
        }
        if (!alive[p]) continue;
        for (const Access& a : passes_[p].accesses) {
            if (!isWrite(a.usage)) needed.insert({a.isImage, a.resource, a.version});
            else if (a.readsPrevious) needed.insert({a.isImage, a.resource, a.from});
        }
    }
    return alive;
}

void FrameGraph::planMemory(const std::vector<bool>& alive, const ImageMemoryFn& imageMemory) {
    memory_ = {};
    aliasedBefore_.assign(images_.size(), {});
    struct Lifetime {
        uint32_t image;
        size_t first, last;
        VkMemoryRequirements requirements;
    };
    std::vector<Lifetime> lifetimes;
    std::vector<int> slot(images_.size(), -1);
    for (size_t p = 0; p < passes_.size(); ++p) {
        if (!alive[p]) continue;
        for (const Access& a : passes_[p].accesses) {
            if (!a.isImage || images_[a.resource].residency != Residency::Transient) continue;
            if (slot[a.resource] < 0) {
                slot[a.resource] = int(lifetimes.size());
                lifetimes.push_back({a.resource, p, p, {}});
            }
            lifetimes[slot[a.resource]].last = p;
        }
    }
    for (Lifetime& l : lifetimes)
        l.requirements = imageMemory ? imageMemory(images_[l.image].desc) : estimateImageMemory(images_[l.image].desc);
    // Largest first, each at the lowest offset of its heap where it overlaps no image alive at the
    // same time; images of different memory types live in heaps of their own.
    std::vector<size_t> order(lifetimes.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return lifetimes[a].requirements.size > lifetimes[b].requirements.size;
    });
    std::vector<TransientMemory::Placement> placed(lifetimes.size());
    for (size_t i : order) {
        const Lifetime& l = lifetimes[i];
        uint32_t heap = 0;
        while (heap < memory_.heaps.size() && memory_.heaps[heap].memoryTypeBits != l.requirements.memoryTypeBits)
            ++heap;
        if (heap == memory_.heaps.size()) memory_.heaps.push_back({0, 1, l.requirements.memoryTypeBits});
        // The ranges taken by images alive at the same time, in offset order.
        std::vector<std::pair<VkDeviceSize, VkDeviceSize>> taken;
        for (size_t j : order) {
            if (j == i) break;
            const Lifetime& other = lifetimes[j];
            if (placed[j].heap != heap || other.last < l.first || l.last < other.first) continue;
            taken.emplace_back(placed[j].offset, placed[j].offset + placed[j].size);
        }
        std::sort(taken.begin(), taken.end());
        VkDeviceSize offset = 0;
        for (auto [begin, end] : taken) {
            if (alignUp(offset, l.requirements.alignment) + l.requirements.size <= begin) break;
            offset = std::max(offset, end);
        }
        offset = alignUp(offset, l.requirements.alignment);
        placed[i] = {l.image, heap, offset, l.requirements.size};
        TransientMemory::Heap& h = memory_.heaps[heap];
        h.size = std::max(h.size, offset + l.requirements.size);
        h.alignment = std::max(h.alignment, l.requirements.alignment);
    }
    // An image placed over memory an earlier one used waits for that one's last accesses.
    for (size_t i = 0; i < lifetimes.size(); ++i)
        for (size_t j = 0; j < lifetimes.size(); ++j) {
            const auto &a = placed[i], &b = placed[j];
            if (a.heap == b.heap && lifetimes[j].last < lifetimes[i].first && b.offset < a.offset + a.size &&
                a.offset < b.offset + b.size)
                aliasedBefore_[a.image].push_back(b.image);
        }
    memory_.placements = std::move(placed);
}

void FrameGraph::compile(const ImageMemoryFn& imageMemory) {
    compiled_.clear();
    const size_t n = passes_.size();
    checkVersions();
    const std::vector<bool> alive = cull();

    // Usage flags of transient images and buffers from every live declaration; a persistent
    // image's flags are its owner's, and must cover what the frame does with it.
    for (size_t p = 0; p < n; ++p) {
        if (!alive[p]) continue;
        for (const Access& a : passes_[p].accesses) {
            if (!a.isImage) {
                if (buffers_[a.resource].frameBuffer)
                    buffers_[a.resource].usage |= stateOf(a.usage, false).bufferUsage;
                continue;
            }
            ImageResource& img = images_[a.resource];
            VkImageUsageFlags usage = stateOf(a.usage, isDepthFormat(img.desc.format)).imageUsage;
            if (img.residency == Residency::Transient) img.desc.usage |= usage;
            else if ((img.desc.usage & usage) != usage)
                throw std::logic_error("frame graph: pass '" + passes_[p].name + "' uses '" + img.name +
                                       "' in a way its image was not created for");
        }
    }
    planMemory(alive, imageMemory);

    // Barrier planning: track the last layout, the last write and the reads since then.
    struct Track {
        VkImageLayout layout;
        VkPipelineStageFlags2 writeStage = 0;
        VkAccessFlags2 writeAccess = 0;
        VkPipelineStageFlags2 readStages = 0;
        bool used = false;
    };
    std::vector<Track> imageTrack(images_.size()), bufferTrack(buffers_.size());
    for (size_t i = 0; i < images_.size(); ++i) {
        imageTrack[i].layout = images_[i].initialLayout;
        if (images_[i].residency == Residency::Persistent) {
            // Persistent images were last written by an earlier submission that the host waited for.
            imageTrack[i].writeStage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
            imageTrack[i].writeAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
        }
    }

    // Last live pass touching each image: attachments not read after it need not be stored.
    std::vector<int> lastUse(images_.size(), -1);
    for (size_t p = 0; p < n; ++p)
        if (alive[p])
            for (const Access& a : passes_[p].accesses)
                if (a.isImage) lastUse[a.resource] = static_cast<int>(p);
    for (auto& img : images_) img.used = img.written = false;

    for (size_t p = 0; p < n; ++p) {
        CompiledPass cp{passes_[p].name, passes_[p].kind, !alive[p], {}, passes_[p].attachments};
        if (alive[p]) {
            for (const Access& a : passes_[p].accesses) {
                bool depth = a.isImage && isDepthFormat(images_[a.resource].desc.format);
                UsageState s = stateOf(a.usage, depth);
                Track& t = a.isImage ? imageTrack[a.resource] : bufferTrack[a.resource];
                VkPipelineStageFlags2 aliasStages = 0;
                VkAccessFlags2 aliasAccess = 0;
                if (a.isImage && !t.used)
                    for (uint32_t earlier : aliasedBefore_[a.resource]) {
                        aliasStages |= imageTrack[earlier].writeStage | imageTrack[earlier].readStages;
                        aliasAccess |= imageTrack[earlier].writeAccess;
                    }
                t.used = true;
                if (a.isImage) images_[a.resource].used = true;
                bool layoutChange = a.isImage && t.layout != s.layout;
                bool afterWrite = t.writeAccess != 0;
                bool writeAfterRead = isWrite(a.usage) && t.readStages != 0;
                // Two accesses in one pass with the same layout need no barrier between them.
                bool samePass = false;
                for (const auto& b : cp.barriers)
                    if (b.resource == a.resource && b.isImage == a.isImage) samePass = true;
                if ((layoutChange || afterWrite || writeAfterRead || aliasStages) && !samePass) {
                    PlannedBarrier b{a.resource,
                                     a.isImage,
                                     t.layout,
                                     a.isImage ? s.layout : VK_IMAGE_LAYOUT_UNDEFINED,
                                     t.writeStage | t.readStages | aliasStages,
                                     t.writeAccess | aliasAccess,
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
                    t.writeStage |= s.stage;
                    t.writeAccess |= s.access & kWriteAccesses;
                    if (a.isImage) images_[a.resource].written = true;
                } else {
                    t.readStages |= s.stage;
                }
            }
            for (auto& att : cp.attachments) {
                if (!att.image.valid()) continue;
                const auto& img = images_[att.image.index];
                if (lastUse[att.image.index] == static_cast<int>(p) && !img.output &&
                    img.residency == Residency::Transient)
                    att.store = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            }
        }
        compiled_.push_back(std::move(cp));
    }
    for (size_t i = 0; i < images_.size(); ++i) images_[i].finalLayout = imageTrack[i].layout;
}

void FrameGraph::realize(FrameBackend& backend) {
    std::vector<ImageDesc> descs;
    std::vector<std::string> names;
    for (const auto& p : memory_.placements) {
        descs.push_back(images_[p.image].desc);
        names.push_back(images_[p.image].name);
    }
    std::vector<ImagePtr> transients = backend.transientImages(memory_, descs, names);
    for (size_t i = 0; i < transients.size(); ++i) images_[memory_.placements[i].image].image = transients[i];
    for (auto& img : images_) {
        if (img.residency != Residency::Persistent || img.image || !img.used) continue;
        MemoryCategoryScope history(MemoryCategory::FrameHistory);
        img.image = backend.createImage(img.desc, img.name);
        img.persistent->image_ = img.image;
    }
    for (auto& b : buffers_) {
        if (!b.frameBuffer || b.usage == 0) continue;
        b.buffer = backend.createFrameBuffer(b.bytes.size(), b.usage, b.name);
        std::memcpy(b.buffer->mapped(), b.bytes.data(), b.bytes.size());
    }
}

void FrameGraph::submitted() {
    for (auto& img : images_) {
        if (img.residency == Residency::Transient || !img.image) continue;
        img.image->layout = img.finalLayout;
        if (img.persistent && img.written) img.persistent->written_ = true;
    }
}

void FrameGraph::execute(Device& device, PipelineCache& pipelines, VkCommandBuffer cmd, Timestamps* timestamps) {
    std::vector<const PipelineCache::Request*> requests;
    for (size_t p = 0; p < passes_.size(); ++p)
        if (!compiled_[p].culled)
            for (const PipelineCache::Request& r : passes_[p].pipelines) requests.push_back(&r);
    pipelines.prepare(requests);
    PassResources resources(*this, device, pipelines);
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
                VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                if (!att.image.valid()) {  // an unused slot: a null view, writes discarded
                    colors.push_back(info);
                    continue;
                }
                const auto& img = images_[att.image.index];
                extent = {img.desc.width, img.desc.height};
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
