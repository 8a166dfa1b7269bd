#include "gpu/pipeline.h"

#include "gpu/context.h"
#include "gpu/pipeline_statistics.h"
#include "gpu/shader_registry.h"
#include "gpu/vk_check.h"

#include <algorithm>
#include <cstdio>

namespace obscura::gpu {
namespace {

// The specialization constants every shader stage gets: the device traits
// (shaders/common/device_traits.glsl, constant 0) and the pipeline's own, built in place: the info
// points at its own members.
struct Specialization {
    Specialization(Device& device, const std::vector<SpecializationConstant>& constants) {
        values.push_back(device.context().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);  // COMPACT_CODE
        entries.push_back({0, 0, sizeof(uint32_t)});
        for (const SpecializationConstant& c : constants) {
            entries.push_back({c.id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
            values.push_back(c.value);
        }
        info = {uint32_t(entries.size()), entries.data(), values.size() * sizeof(uint32_t), values.data()};
    }
    Specialization(const Specialization&) = delete;
    Specialization& operator=(const Specialization&) = delete;

    std::vector<uint32_t> values;  // VkBool32 and uint constants alike are 32 bits
    std::vector<VkSpecializationMapEntry> entries;
    VkSpecializationInfo info{};
};

}  // namespace

std::string specializationSuffix(const std::vector<SpecializationConstant>& constants) {
    std::string suffix;
    char text[32];
    for (const SpecializationConstant& c : constants) {
        std::snprintf(text, sizeof(text), ".c%u=%x", c.id, c.value);
        suffix += text;
    }
    return suffix;
}

VkPipelineCreateFlags Pipeline::captureFlags() const {
    return device_.context().pipelineExecutableFunctions().statistics ? VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR
                                                                      : 0;
}

VkShaderModule Pipeline::loadModule(const std::string& name) {
    auto words = findShader(name);
    if (words.empty()) throw DeviceError("shader '" + name + "' is not embedded in the plugin");
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = words.size_bytes();
    ci.pCode = words.data();
    VkShaderModule module = VK_NULL_HANDLE;
    vkCheck(vkCreateShaderModule(device_.vk(), &ci, nullptr, &module), "vkCreateShaderModule");
    return module;
}

void Pipeline::createLayout(const std::vector<BindingDesc>& bindings, uint32_t pushConstantSize,
                            VkShaderStageFlags stages, uint32_t pushedSamplers) {
    bindings_ = bindings;
    std::vector<VkDescriptorSetLayoutBinding> vkBindings;
    for (const auto& b : bindings) vkBindings.push_back({b.binding, b.type, 1, stages, nullptr});
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = static_cast<uint32_t>(vkBindings.size());
    li.pBindings = vkBindings.data();
    vkCheck(vkCreateDescriptorSetLayout(device_.vk(), &li, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
    std::vector<VkDescriptorSetLayout> setLayouts = {setLayout_};
    pushedSamplers_ = pushedSamplers;
    if (pushedSamplers > 0) {
        std::vector<VkDescriptorSetLayoutBinding> pushed;
        for (uint32_t b = 0; b < pushedSamplers; ++b)
            pushed.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr});
        VkDescriptorSetLayoutCreateInfo pushInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        pushInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
        pushInfo.bindingCount = pushedSamplers;
        pushInfo.pBindings = pushed.data();
        vkCheck(vkCreateDescriptorSetLayout(device_.vk(), &pushInfo, nullptr, &pushSetLayout_),
                "vkCreateDescriptorSetLayout");
        setLayouts.push_back(pushSetLayout_);
    }
    VkPushConstantRange range{stages, 0, pushConstantSize};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = static_cast<uint32_t>(setLayouts.size());
    pli.pSetLayouts = setLayouts.data();
    pli.pushConstantRangeCount = pushConstantSize ? 1 : 0;
    pli.pPushConstantRanges = &range;
    vkCheck(vkCreatePipelineLayout(device_.vk(), &pli, nullptr, &layout_), "vkCreatePipelineLayout");
}

Pipeline::Pipeline(Device& device, const ComputePipelineDesc& desc) : device_(device) {
    bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    createLayout(desc.bindings, desc.pushConstantSize, VK_SHADER_STAGE_COMPUTE_BIT);
    VkShaderModule module = loadModule(desc.shader);
    const Specialization specialization(device_, desc.specialization);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT,
                module, "main", &specialization.info};
    ci.layout = layout_;
    ci.flags = captureFlags();
    VkResult r = vkCreateComputePipelines(device_.vk(), device_.pipelineCache(), 1, &ci, nullptr, &pipeline_);
    vkDestroyShaderModule(device_.vk(), module, nullptr);
    vkCheck(r, "vkCreateComputePipelines");
    logPipelineStatistics(device_.context(), pipeline_, desc.shader);
}

Pipeline::Pipeline(Device& device, const GraphicsPipelineDesc& desc) : device_(device) {
    bindPoint_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
    createLayout(desc.bindings, desc.pushConstantSize, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                 desc.pushedSamplers);
    VkShaderModule vs = loadModule(desc.vertexShader);
    VkShaderModule fs = desc.fragmentShader.empty() ? VK_NULL_HANDLE : loadModule(desc.fragmentShader);
    const Specialization specialization(device_, desc.specialization);
    VkPipelineShaderStageCreateInfo stages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vs, "main",
         &specialization.info},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fs, "main",
         &specialization.info}};

    std::vector<VkVertexInputBindingDescription> bindings;
    for (uint32_t b = 0; b < desc.vertexStrides.size(); ++b)
        bindings.push_back({b, desc.vertexStrides[b], VK_VERTEX_INPUT_RATE_VERTEX});
    std::vector<VkVertexInputAttributeDescription> attrs;
    for (const auto& a : desc.vertexAttributes) attrs.push_back({a.location, a.binding, a.format, a.offset});
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
    vi.pVertexBindingDescriptions = bindings.data();
    vi.vertexAttributeDescriptionCount = static_cast<uint32_t>(attrs.size());
    vi.pVertexAttributeDescriptions = attrs.data();
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = desc.cullMode;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    rs.depthBiasEnable = desc.depthBiasConstant != 0.0f || desc.depthBiasSlope != 0.0f;
    rs.depthBiasConstantFactor = desc.depthBiasConstant;
    rs.depthBiasSlopeFactor = desc.depthBiasSlope;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = desc.samples;
    ms.sampleShadingEnable = desc.sampleShading ? VK_TRUE : VK_FALSE;
    ms.minSampleShading = desc.sampleShading ? 1.0f : 0.0f;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = desc.depthTest;
    ds.depthWriteEnable = desc.depthWrite;
    ds.depthCompareOp = desc.depthCompare;
    ds.stencilTestEnable = desc.stencil.enabled;
    ds.front = {VK_STENCIL_OP_KEEP, desc.stencil.passOp, VK_STENCIL_OP_KEEP, desc.stencil.compare, 0xffu, 0u,
                desc.stencil.reference};
    ds.back = ds.front;
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (size_t i = 0; i < blends.size(); ++i) {
        VkPipelineColorBlendAttachmentState& b = blends[i];
        if ((desc.untouchedColorAttachments >> i & 1u) != 0) continue;
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
        if (!desc.premultipliedOverBlend) continue;
        b.blendEnable = VK_TRUE;
        b.srcColorBlendFactor = b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        b.dstColorBlendFactor = b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = static_cast<uint32_t>(blends.size());
    cb.pAttachments = blends.data();
    VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_STENCIL_WRITE_MASK};
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = desc.stencil.enabled ? 3 : 2;
    dyn.pDynamicStates = dynamic;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;
    rendering.stencilAttachmentFormat = hasStencil(desc.depthFormat) ? desc.depthFormat : VK_FORMAT_UNDEFINED;

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    ci.stageCount = fs ? 2 : 1;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dyn;
    ci.layout = layout_;
    ci.flags = captureFlags();
    VkResult r = vkCreateGraphicsPipelines(device_.vk(), device_.pipelineCache(), 1, &ci, nullptr, &pipeline_);
    vkDestroyShaderModule(device_.vk(), vs, nullptr);
    if (fs) vkDestroyShaderModule(device_.vk(), fs, nullptr);
    vkCheck(r, "vkCreateGraphicsPipelines");
    logPipelineStatistics(device_.context(), pipeline_, desc.vertexShader + " + " + desc.fragmentShader);
}

Pipeline::~Pipeline() {
    VkDevice d = device_.vk();
    VkPipeline p = pipeline_;
    VkPipelineLayout l = layout_;
    VkDescriptorSetLayout s = setLayout_;
    VkDescriptorSetLayout pushed = pushSetLayout_;
    device_.retire([d, p, l, s, pushed] {
        vkDestroyPipeline(d, p, nullptr);
        vkDestroyPipelineLayout(d, l, nullptr);
        vkDestroyDescriptorSetLayout(d, s, nullptr);
        vkDestroyDescriptorSetLayout(d, pushed, nullptr);
    });
}

DescriptorWriter::DescriptorWriter(Device& device, const Pipeline& pipeline) : device_(device), pipeline_(pipeline) {
    // Reserve so the pointers stored in writes_ stay valid.
    images_.reserve(pipeline.bindings().size());
    buffers_.reserve(pipeline.bindings().size());
}

DescriptorWriter& DescriptorWriter::sampled(uint32_t binding, VkImageView view, VkSampler sampler, VkImageLayout layout) {
    images_.push_back({sampler, view, layout});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &images_.back();
    writes_.push_back(w);
    written_.push_back(binding);
    return *this;
}

DescriptorWriter& DescriptorWriter::storageImage(uint32_t binding, VkImageView view) {
    images_.push_back({VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.pImageInfo = &images_.back();
    writes_.push_back(w);
    written_.push_back(binding);
    return *this;
}

DescriptorWriter& DescriptorWriter::buffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range) {
    auto it = std::find_if(pipeline_.bindings().begin(), pipeline_.bindings().end(),
                           [&](const BindingDesc& b) { return b.binding == binding; });
    if (it == pipeline_.bindings().end()) throw DeviceError("descriptor binding not declared by the pipeline");
    buffers_.push_back({buffer, offset, range});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = it->type;
    w.pBufferInfo = &buffers_.back();
    writes_.push_back(w);
    written_.push_back(binding);
    return *this;
}

void DescriptorWriter::bind(VkCommandBuffer cmd) {
    for (const auto& b : pipeline_.bindings())
        if (std::find(written_.begin(), written_.end(), b.binding) == written_.end())
            throw DeviceError("descriptor binding " + std::to_string(b.binding) + " has no resource");
    VkDescriptorSet set = device_.allocateDescriptorSet(pipeline_.setLayout());
    for (auto& w : writes_) w.dstSet = set;
    vkUpdateDescriptorSets(device_.vk(), static_cast<uint32_t>(writes_.size()), writes_.data(), 0, nullptr);
    vkCmdBindPipeline(cmd, pipeline_.bindPoint(), pipeline_.vk());
    vkCmdBindDescriptorSets(cmd, pipeline_.bindPoint(), pipeline_.layout(), 0, 1, &set, 0, nullptr);
}

void pushSampledImages(Device& device, VkCommandBuffer cmd, const Pipeline& pipeline,
                       const std::vector<VkDescriptorImageInfo>& images) {
    if (images.size() != pipeline.pushedSamplers())
        throw DeviceError("the pipeline pushes " + std::to_string(pipeline.pushedSamplers()) + " samplers, not " +
                          std::to_string(images.size()));
    std::vector<VkWriteDescriptorSet> writes;
    for (uint32_t b = 0; b < images.size(); ++b) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = b;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        w.pImageInfo = &images[b];
        writes.push_back(w);
    }
    device.context().cmdPushDescriptorSet()(cmd, pipeline.bindPoint(), pipeline.layout(), 1,
                                            static_cast<uint32_t>(writes.size()), writes.data());
}

void dispatch2D(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t groupSize) {
    vkCmdDispatch(cmd, (width + groupSize - 1) / groupSize, (height + groupSize - 1) / groupSize, 1);
}

}  // namespace obscura::gpu
