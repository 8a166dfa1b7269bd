// The frame graph (after Filament's FrameGraph and Granite's render graph): passes declare the
// images and buffers they read and write with a usage. Handles are versioned: a write returns the
// resource's next version, and a pass reads the version it was handed; reading a version after a
// newer one was written is an error compile() reports. compile() culls passes whose results
// nobody uses, derives every layout transition and barrier, the load/store ops of attachments,
// and where transient images live in memory: images whose lifetimes do not overlap share it.
// execute() records barriers, begins dynamic rendering for raster passes, wraps each pass in
// timestamps and calls its record callback. Passes never write barriers by hand.
//
// Images that outlive the frame (histories, the shadow atlas, the reference's sum, the
// environment maps) are imported: the graph starts from the layout the last frame left them in
// (Image::layout) and, once the frame is submitted, leaves theirs for the next one. A pass that
// writes one is never culled: a later frame reads it.
#pragma once

#include "gpu/device.h"
#include "gpu/pipeline_cache.h"

#include <functional>
#include <string>
#include <vector>

namespace obscura::gpu {

class FrameBackend;
class HistoryImages;
class PersistentImage;
class Timestamps;

enum class Usage {
    ColorAttachment,        // write
    DepthStencilAttachment, // write (depth test + write, stencil)
    SampledCompute,         // read through a sampler or texelFetch in a compute shader
    SampledFragment,        // read in a fragment shader
    StorageImageRead,       // imageLoad in compute
    StorageImageWrite,      // imageStore in compute
    StorageBufferRead,      // compute
    StorageBufferReadGraphics,  // a storage buffer read in vertex or fragment shaders
    StorageBufferWrite,     // compute
    IndirectCommandRead,    // the commands of indirect draws
    TransferSrc,
    TransferDst,
};

bool isWrite(Usage usage);

// A resource of the graph at one version: version 0 is what the resource holds before any pass
// of the frame writes it (nothing, for a transient); each write makes the next.
struct [[nodiscard]] ImageHandle {
    uint32_t index = UINT32_MAX;
    uint32_t version = 0;
    bool valid() const { return index != UINT32_MAX; }
};
struct [[nodiscard]] BufferHandle {
    uint32_t index = UINT32_MAX;
    uint32_t version = 0;
    bool valid() const { return index != UINT32_MAX; }
};

enum class PassKind { Raster, Compute, Transfer };

// What compile() decided for one access: the barrier before the pass (if any).
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
    ImageHandle image;  // invalid: a colour slot left unbound (PassBuilder::unusedColorAttachment)
    bool depth = false;
    VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_LOAD;
    VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
    VkClearValue clear{};
};

// Where compile() put the transient images: heaps of memory, each image at an offset in one.
struct TransientMemory {
    struct Heap {
        VkDeviceSize size = 0;
        VkDeviceSize alignment = 1;
        uint32_t memoryTypeBits = 0;
    };
    struct Placement {
        uint32_t image;  // the graph's image index
        uint32_t heap;
        VkDeviceSize offset;
        VkDeviceSize size;
    };
    std::vector<Heap> heaps;
    std::vector<Placement> placements;
    VkDeviceSize bytes() const;          // the heaps together
    VkDeviceSize unaliasedBytes() const;  // every image in memory of its own
};

// The memory an image of `desc` takes (VkMemoryRequirements): size, alignment, memory types.
using ImageMemoryFn = std::function<VkMemoryRequirements(const ImageDesc&)>;

// What a pass's record callback works with: the device, its pipelines (those it declared built
// before the frame records), and the Vulkan objects behind the graph's handles.
class PassResources {
public:
    PassResources(const class FrameGraph& graph, Device& device, PipelineCache& pipelines)
        : graph_(graph), device_(device), pipelines_(pipelines) {}
    Device& device() const { return device_; }
    PipelineCache& pipelines() const { return pipelines_; }
    VkImage image(ImageHandle h) const;
    VkImageView view(ImageHandle h) const;
    VkImageView stencilView(ImageHandle h) const;
    // The view imageStore writes through (Image::storageView where the image has one).
    VkImageView storageView(ImageHandle h) const;
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

using RecordFn = std::function<void(VkCommandBuffer, const PassResources&)>;

class FrameGraph {
public:
    class PassBuilder {
    public:
        void read(ImageHandle h, Usage usage);
        void read(BufferHandle h, Usage usage);
        // Returns the version this pass writes; several writes of one resource in a pass are one.
        ImageHandle write(ImageHandle h, Usage usage);
        BufferHandle write(BufferHandle h, Usage usage);
        // A raster pass's attachments, starting with what `h` holds (Keep: the pass blends or
        // tests against it), with nothing (Discard: the pass writes every texel), or cleared.
        enum class Load { Keep, Discard };
        ImageHandle colorAttachment(ImageHandle h, Load load = Load::Keep);
        ImageHandle colorAttachment(ImageHandle h, VkClearColorValue clear);
        ImageHandle depthStencilAttachment(ImageHandle h, Load load = Load::Keep);
        ImageHandle depthStencilAttachment(ImageHandle h, VkClearDepthStencilValue clear);
        // A colour slot bound to nothing (VK_NULL_HANDLE), so that the attachments after it keep
        // their locations; the pass's pipelines name VK_FORMAT_UNDEFINED there.
        void unusedColorAttachment();
        // A pipeline the pass binds as it records: execute() builds the missing pipelines of every
        // pass it records before recording any, together (PipelineCache::prepare).
        void usesPipeline(PipelineCache::Request request);

    private:
        friend class FrameGraph;
        PassBuilder(FrameGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
        ImageHandle attachment(ImageHandle h, bool depth, VkAttachmentLoadOp load, VkClearValue clear);
        FrameGraph& graph_;
        uint32_t pass_;
    };

    FrameGraph() = default;
    FrameGraph(const FrameGraph&) = delete;
    FrameGraph& operator=(const FrameGraph&) = delete;

    // A transient image owned by the graph for this frame; usage flags come from the declarations.
    ImageHandle createImage(const std::string& name, const ImageDesc& desc);
    // A texture: read-only, left by its upload visible to shaders in SHADER_READ_ONLY_OPTIMAL, so
    // its reads need no barrier; a pass that writes it is an error.
    ImageHandle importTexture(const std::string& name, ImagePtr texture);
    // An image kept from frame to frame: created (again, when `desc` differs from its image's) as
    // the frame runs; until a frame has written it, it holds nothing.
    ImageHandle importPersistent(const std::string& name, PersistentImage& image, const ImageDesc& desc);
    // A history (Granite's history input): `previous` is what the last frame wrote into `name`,
    // read-only; `current` is this frame's, for a pass to write and the next frame to read.
    // `previousEmpty` on the first frame and after the images were created again: nothing to read
    // there (the handle is still bound, since a binding needs a resource).
    struct History {
        ImageHandle previous;
        ImageHandle current;
        bool previousEmpty;
    };
    [[nodiscard]] History addHistory(const std::string& name, HistoryImages& history, const ImageDesc& desc);
    BufferHandle importBuffer(const std::string& name, BufferPtr buffer);
    // A host-visible buffer for this frame holding `bytes` (a pass's constants), made as it runs.
    BufferHandle createBuffer(const std::string& name, std::vector<uint8_t> bytes);

    void addPass(const std::string& name, PassKind kind, const std::function<void(PassBuilder&)>& setup,
                 RecordFn record);
    // Results the host needs: passes that contribute to these are kept, others culled.
    void markOutput(ImageHandle h);
    void markOutput(BufferHandle h);

    // Culling, version checks, barrier planning and the transient images' memory; pure logic (no
    // Vulkan calls), unit-tested on its own. `imageMemory` sizes the images (an estimate from
    // their texels when empty). Throws std::logic_error for a read of a transient nothing wrote,
    // and for a read or write of a version older than one already written.
    void compile(const ImageMemoryFn& imageMemory = {});
    // Makes what the compiled frame needs: transient images placed as compile() planned, new
    // persistent images and this frame's buffers.
    void realize(FrameBackend& backend);
    // Records every pass that was not culled, once the pipelines they declared are built.
    void execute(Device& device, PipelineCache& pipelines, VkCommandBuffer cmd, Timestamps* timestamps);
    // The recorded frame was submitted: persistent images keep the layouts it leaves them in, and
    // persistent images it wrote hold something.
    void submitted();

    // Introspection for tests and the benchmark.
    struct CompiledPass {
        std::string name;
        PassKind kind;
        bool culled;
        std::vector<PlannedBarrier> barriers;
        std::vector<Attachment> attachments;
    };
    const std::vector<CompiledPass>& compiled() const { return compiled_; }
    const TransientMemory& transientMemory() const { return memory_; }
    const ImageDesc& imageDesc(ImageHandle h) const { return images_.at(h.index).desc; }
    uint32_t imageCount() const { return uint32_t(images_.size()); }
    uint32_t bufferCount() const { return uint32_t(buffers_.size()); }
    const std::string& imageName(uint32_t index) const { return images_.at(index).name; }
    const std::string& bufferName(uint32_t index) const { return buffers_.at(index).name; }

private:
    friend class PassResources;
    struct Access {
        uint32_t resource;
        bool isImage;
        Usage usage;
        uint32_t version;  // read: the version read; write: the version written
        // A write that keeps what the resource held (an attachment loaded, not cleared): it reads
        // version `from` too.
        bool readsPrevious = false;
        uint32_t from = 0;  // write: the version written over
    };
    struct Pass {
        std::string name;
        PassKind kind;
        std::vector<Access> accesses;
        std::vector<Attachment> attachments;
        RecordFn record;
        std::vector<PipelineCache::Request> pipelines;
    };
    enum class Residency { Transient, Texture, Persistent };
    struct ImageResource {
        std::string name;
        ImageDesc desc;
        ImagePtr image;  // imported, or made by realize()
        Residency residency = Residency::Transient;
        PersistentImage* persistent = nullptr;
        bool output = false;
        uint32_t versions = 0;  // written so far, as passes are declared
        VkImageLayout initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        VkImageLayout finalLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        bool used = false;     // by a pass that is not culled
        bool written = false;  // by a pass that is not culled
    };
    struct BufferResource {
        std::string name;
        BufferPtr buffer;
        std::vector<uint8_t> bytes;  // a buffer of this frame: its contents
        bool frameBuffer = false;
        VkBufferUsageFlags usage = 0;
        bool output = false;
        uint32_t versions = 0;
    };
    ImageHandle addImage(ImageResource resource);
    uint32_t writeVersion(uint32_t pass, uint32_t resource, bool isImage, uint32_t version, Usage usage);
    std::vector<bool> cull() const;
    void checkVersions() const;
    void planMemory(const std::vector<bool>& alive, const ImageMemoryFn& imageMemory);

    std::vector<Pass> passes_;
    std::vector<ImageResource> images_;
    std::vector<BufferResource> buffers_;
    std::vector<CompiledPass> compiled_;
    TransientMemory memory_;
    // For each transient image, the images placed in its memory earlier in the frame.
    std::vector<std::vector<uint32_t>> aliasedBefore_;
};

}  // namespace obscura::gpu
