// Compute and graphics pipelines built from embedded SPIR-V, with one descriptor set whose
// layout each pass declares, and a small writer that fills a per-frame set and binds it.
#pragma once

#include "gpu/device.h"

#include <string>
#include <vector>

namespace obscura::gpu {

struct BindingDesc {
    uint32_t binding;
    VkDescriptorType type;
};

// A specialization constant beyond the device traits (constant_id 0, shaders/common/
// device_traits.glsl): a pipeline built for what a frame holds leaves out the code of what it
// lacks. A shader that declares no constant of the id ignores it.
struct SpecializationConstant {
    uint32_t id;
    uint32_t value;
};

// The constants as part of a pipeline's name in the PipelineCache: "" for none, else
// ".c<id>=<hex value>" each.
std::string specializationSuffix(const std::vector<SpecializationConstant>& constants);

struct VertexAttribute {
    uint32_t location;
    VkFormat format;
    uint32_t offset;
    uint32_t binding = 0;  // index into GraphicsPipelineDesc::vertexStrides
};

struct GraphicsPipelineDesc {
    std::string vertexShader;
    std::string fragmentShader;  // empty: a depth-only pipeline (shadow maps)
    std::vector<BindingDesc> bindings;
    // Set 1: this many combined image samplers (bindings 0..n-1) that change per draw, pushed with
    // pushSampledImages (VK_KHR_push_descriptor) instead of allocated.
    uint32_t pushedSamplers = 0;
    uint32_t pushConstantSize = 0;
    std::vector<uint32_t> vertexStrides;  // one per vertex buffer binding (per-vertex rate)
    std::vector<VertexAttribute> vertexAttributes;
    std::vector<VkFormat> colorFormats;
    // Colour attachments (bit i: attachment i) the pipeline leaves as they are: write mask 0.
    uint32_t untouchedColorAttachments = 0;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    // One fragment shader invocation per covered sample (sample shading, minSampleShading 1).
    bool sampleShading = false;
    // Every colour attachment blends "over" with premultiplied colour: src + dst * (1 - src alpha)
    // (Porter & Duff 1984), the alpha likewise.
    bool premultipliedOverBlend = false;
    bool depthTest = true;
    bool depthWrite = true;
    // Rasteriser depth bias (constant and slope-scaled factors); both 0 leave it off.
    float depthBiasConstant = 0.0f;
    float depthBiasSlope = 0.0f;
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
    VkCompareOp depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    // Stencil, front and back alike: `passOp` where both tests pass; the write mask is dynamic
    // state (vkCmdSetStencilWriteMask per draw), the compare mask all bits.
    struct Stencil {
        bool enabled = false;
        VkCompareOp compare = VK_COMPARE_OP_ALWAYS;
        VkStencilOp passOp = VK_STENCIL_OP_KEEP;
        uint32_t reference = 0;
    } stencil;
    std::vector<SpecializationConstant> specialization;  // both stages
};

struct ComputePipelineDesc {
    std::string shader;
    std::vector<BindingDesc> bindings;
    uint32_t pushConstantSize = 0;
    std::vector<SpecializationConstant> specialization;
};

class Pipeline {
public:
    Pipeline(Device& device, const ComputePipelineDesc& desc);
    Pipeline(Device& device, const GraphicsPipelineDesc& desc);
    ~Pipeline();
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    VkPipeline vk() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    VkDescriptorSetLayout setLayout() const { return setLayout_; }
    VkPipelineBindPoint bindPoint() const { return bindPoint_; }
    const std::vector<BindingDesc>& bindings() const { return bindings_; }
    uint32_t pushedSamplers() const { return pushedSamplers_; }

private:
    void createLayout(const std::vector<BindingDesc>& bindings, uint32_t pushConstantSize, VkShaderStageFlags stages,
                      uint32_t pushedSamplers = 0);
    VkShaderModule loadModule(const std::string& name);
    // VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR where the context captures them
    // (gpu/pipeline_statistics.h).
    VkPipelineCreateFlags captureFlags() const;

    Device& device_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout pushSetLayout_ = VK_NULL_HANDLE;
    uint32_t pushedSamplers_ = 0;
    VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    std::vector<BindingDesc> bindings_;
};

// Fills a fresh per-frame descriptor set for `pipeline` and binds it. Every binding the pipeline
// declares must be written: a missing resource is an error, not a silently black pass.
class DescriptorWriter {
public:
    DescriptorWriter(Device& device, const Pipeline& pipeline);
    DescriptorWriter& sampled(uint32_t binding, VkImageView view, VkSampler sampler,
                              VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    DescriptorWriter& storageImage(uint32_t binding, VkImageView view);
    DescriptorWriter& buffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                             VkDeviceSize range = VK_WHOLE_SIZE);
    void bind(VkCommandBuffer cmd);

private:
    Device& device_;
    const Pipeline& pipeline_;
    std::vector<VkWriteDescriptorSet> writes_;
    std::vector<VkDescriptorImageInfo> images_;
    std::vector<VkDescriptorBufferInfo> buffers_;
    std::vector<uint32_t> written_;
};

// Pushes set 1 of a graphics pipeline: one combined image sampler (SHADER_READ_ONLY_OPTIMAL) per
// GraphicsPipelineDesc::pushedSamplers, for the draws recorded after it.
void pushSampledImages(Device& device, VkCommandBuffer cmd, const Pipeline& pipeline,
                       const std::vector<VkDescriptorImageInfo>& images);

// Dispatch enough 8x8 groups to cover width x height.
void dispatch2D(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t groupSize = 8);

}  // namespace obscura::gpu
