// The frame graph (after Granite's render graph and Filament's FrameGraph): passes declare the
// images and buffers they read and write with a usage; compile() culls passes whose results
// nobody uses and derives every layout transition and barrier, and the load/store ops of
// attachments; execute() creates transient images, records barriers, begins dynamic rendering
// for raster passes, wraps each pass in timestamps and calls its record callback.
// Passes never write barriers by hand.
#pragma once

#include "gpu/device.h"
#include "gpu/pipeline_cache.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace obscura::gpu {

class Timestamps;

enum class Usage {
    ColorAttachment,        // write
    DepthStencilAttachment, // write (depth test + write, stencil)
    SampledCompute,         // read through a sampler or texelFetch in a compute shader
    SampledFragment,        // read in a fragment shader
    StorageImageRead,       // imageLoad in compute
    StorageImageWrite,      // imageStore in compute
    StorageBufferRead,      // compute
    StorageBufferReadFragment,  // a storage buffer read in a fragment shader
    StorageBufferWrite,     // compute
    TransferSrc,
    TransferDst,
};

bool isWrite(Usage usage);

struct ImageHandle {
    uint32_t index = UINT32_MAX;
    bool valid() const { return index != UINT32_MAX; }
};
struct BufferHandle {
    uint32_t index = UINT32_MAX;
    bool valid() const { return index != UINT32_MAX; }
};

enum class PassKind { Raster, Compute, Transfer };

// What compile() decided for one image access: the barrier before the pass (if any).
struct PlannedBarrier {
    uint32_t resource;
    bool isImage;
    VkImageLayout oldLayout;
    VkImageLayout newLayout;
    VkPipelineStageFlags2 srcStage;
    VkAccessFlags2 srcAccess;
    VkPipelineStageFlags2 dstStage;
    VkAccessFlags2 dstAccess;
};

struct Attachment {
    ImageHandle image;
    bool depth = false;
    VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_LOAD;
    VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
    VkClearValue clear{};
};

// What a pass's record callback works with: the device, its pipelines (compiled the first time a
// pass records), and the Vulkan objects behind the graph's handles.
class PassResources {
public:
    PassResources(const class FrameGraph& graph, Device& device, PipelineCache& pipelines)
        : graph_(graph), device_(device), pipelines_(pipelines) {}
    Device& device() const { return device_; }
    PipelineCache& pipelines() const { return pipelines_; }
    VkImage image(ImageHandle h) const;
    VkImageView view(ImageHandle h) const;
    VkImageView stencilView(ImageHandle h) const;
    // One mip level of a storage image with mips (Image::levelViews).
    VkImageView levelView(ImageHandle h, uint32_t level) const;
    const ImageDesc& desc(ImageHandle h) const;
    VkBuffer buffer(BufferHandle h) const;
    VkDeviceSize bufferSize(BufferHandle h) const;

private:
    const class FrameGraph& graph_;
    Device& device_;
    PipelineCache& pipelines_;
};

// Transient images live across frames here, so a steady frame allocates nothing: an image is
// reused by the next frame that asks for the same description, and released when a frame does
// not use it.
class TransientImagePool {
public:
    explicit TransientImagePool(Device& device) : device_(device) {}
    Device& device() { return device_; }
    ImagePtr acquire(const ImageDesc& desc, const std::string& name);
    void endFrame();

private:
    struct Entry {
        ImagePtr image;
        bool usedThisFrame = false;
    };
    Device& device_;
    std::vector<Entry> entries_;
};

using RecordFn = std::function<void(VkCommandBuffer, const PassResources&)>;

class FrameGraph {
public:
    class PassBuilder {
    public:
        ImageHandle read(ImageHandle h, Usage usage);
        ImageHandle write(ImageHandle h, Usage usage);
        BufferHandle read(BufferHandle h, Usage usage);
        BufferHandle write(BufferHandle h, Usage usage);
        // A raster pass's attachments; clears happen through the load op.
        ImageHandle colorAttachment(ImageHandle h, std::optional<VkClearColorValue> clear = std::nullopt);
        ImageHandle depthStencilAttachment(ImageHandle h, std::optional<VkClearDepthStencilValue> clear = std::nullopt);

    private:
        friend class FrameGraph;
        PassBuilder(FrameGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
        FrameGraph& graph_;
        uint32_t pass_;
    };

    FrameGraph() = default;

    // A transient image owned by the graph for this frame; usage flags come from the declarations.
    ImageHandle createImage(const std::string& name, const ImageDesc& desc);
    // A persistent image (history, readback source) in `layout` now; left as the graph leaves it.
    ImageHandle importImage(const std::string& name, ImagePtr image, VkImageLayout currentLayout);
    BufferHandle importBuffer(const std::string& name, BufferPtr buffer);

    void addPass(const std::string& name, PassKind kind, const std::function<void(PassBuilder&)>& setup,
                 RecordFn record);
    // Results the host needs: passes that contribute to these are kept, others culled.
    void markOutput(ImageHandle h);
    void markOutput(BufferHandle h);

    // Culling and barrier planning; pure logic (no Vulkan calls), unit-tested on its own.
    // Throws std::logic_error for a read of a resource nothing wrote.
    void compile();
    // Takes transient images from `pool` and records every pass that was not culled.
    void execute(TransientImagePool& pool, PipelineCache& pipelines, VkCommandBuffer cmd, Timestamps* timestamps);

    // Introspection for tests and the benchmark.
    struct CompiledPass {
        std::string name;
        PassKind kind;
        bool culled;
        std::vector<PlannedBarrier> barriers;
        std::vector<Attachment> attachments;
    };
    const std::vector<CompiledPass>& compiled() const { return compiled_; }
    // Final layout of an image after the frame (to track imported images across frames).
    VkImageLayout finalLayout(ImageHandle h) const;
    const ImageDesc& imageDesc(ImageHandle h) const { return images_.at(h.index).desc; }

private:
    friend class PassResources;
    struct Access {
        uint32_t resource;
        bool isImage;
        Usage usage;
    };
    struct Pass {
        std::string name;
        PassKind kind;
        std::vector<Access> accesses;
        std::vector<Attachment> attachments;
        RecordFn record;
    };
    struct ImageResource {
        std::string name;
        ImageDesc desc;
        ImagePtr image;       // imported or created at execute
        bool transient = true;
        VkImageLayout initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        VkImageLayout finalLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        bool output = false;
    };
    struct BufferResource {
        std::string name;
        BufferPtr buffer;
        bool output = false;
    };

    std::vector<Pass> passes_;
    std::vector<ImageResource> images_;
    std::vector<BufferResource> buffers_;
    std::vector<CompiledPass> compiled_;
};

}  // namespace obscura::gpu
