#include "passes/aov_readback.h"
#include "generated/shader_layouts.h"

namespace obscura::passes {
namespace {

struct PackPush {
    uint32_t aov;
    uint32_t width;
    uint32_t height;
    uint32_t alphaIsCoverage;
};
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, aov);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, width);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, height);
OBSCURA_SHADER_OFFSET(PackPush, aov_pack_comp::Push, alphaIsCoverage);

gpu::ComputePipelineDesc describeAovPackPipeline() {
    return {"aov_pack.comp",
            {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
             {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
             {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
             {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
             {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
             {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
             {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
             {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
             {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
             {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
             {10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
             {11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
            sizeof(PackPush)};
}

}  // namespace

void addAovReadbackPass(gpu::FrameGraph& graph, PipelineCache& pipelines, const FrameScene& scene,
                        const GBuffer& gb, gpu::ImageHandle hdrColor, HdrAlpha hdrAlpha,
                        gpu::ImageHandle transparentCoverage, gpu::ImageHandle display, gpu::ImageHandle velocity,
                        const std::vector<AovRequest>& requests) {
    if (requests.empty()) return;
    // The pack writes `targets`; where a device-local staging buffer exists, a copy pass then
    // moves it to the host-visible destination.
    std::vector<gpu::BufferHandle> targets, copySources, copyDestinations;
    for (const auto& r : requests) {
        gpu::BufferHandle destination = graph.importBuffer("aov", r.destination);
        graph.markOutput(destination);
        if (r.deviceStaging) {
            targets.push_back(graph.importBuffer("aov.staging", r.deviceStaging));
            copySources.push_back(targets.back());
            copyDestinations.push_back(destination);
        } else {
            targets.push_back(destination);
        }
    }
    const gpu::Pipeline& pipeline = pipelines.get<gpu::ComputePipelineDesc>("aov_pack", describeAovPackPipeline);
    gpu::Device& device = pipelines.device();
    graph.addPass(
        "aov_readback", gpu::PassKind::Compute,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(gb.depth, gpu::Usage::SampledCompute);
            pass.read(gb.normalRoughness, gpu::Usage::SampledCompute);
            pass.read(gb.albedoMetallic, gpu::Usage::SampledCompute);
            pass.read(gb.instance, gpu::Usage::SampledCompute);
            pass.read(hdrColor, gpu::Usage::SampledCompute);
            pass.read(transparentCoverage, gpu::Usage::SampledCompute);
            pass.read(velocity, gpu::Usage::SampledCompute);
            pass.read(display, gpu::Usage::StorageImageRead);
            for (auto h : targets) pass.write(h, gpu::Usage::StorageBufferWrite);
        },
        [&device, &pipeline, &scene, gb, hdrColor, hdrAlpha, transparentCoverage, display, velocity, targets, requests](
            VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkSampler nearest = device.nearestClampSampler();
            for (size_t i = 0; i < requests.size(); ++i) {
                gpu::DescriptorWriter(device, pipeline)
                    .buffer(0, scene.camera->buffer)
                    .buffer(1, scene.instances->buffer)
                    .sampled(2, res.view(gb.depth), nearest, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
                    .sampled(3, res.view(gb.normalRoughness), nearest)
                    .sampled(4, res.view(gb.albedoMetallic), nearest)
                    .sampled(5, res.view(gb.instance), nearest)
                    .sampled(6, res.view(hdrColor), nearest)
                    .storageImage(7, res.view(display))
                    .buffer(8, res.buffer(targets[i]))
                    .buffer(9, res.buffer(targets[i]))
                    .sampled(10, res.view(transparentCoverage), nearest)
                    .sampled(11, res.view(velocity), nearest)
                    .bind(cmd);
                PackPush push{static_cast<uint32_t>(requests[i].aov), scene.width, scene.height,
                              hdrAlpha == HdrAlpha::Coverage ? 1u : 0u};
                vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
                gpu::dispatch2D(cmd, scene.width, scene.height);
            }
        });
    if (copySources.empty()) return;
    graph.addPass(
        "aov_copy", gpu::PassKind::Transfer,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            for (size_t i = 0; i < copySources.size(); ++i) {
                pass.read(copySources[i], gpu::Usage::TransferSrc);
                pass.write(copyDestinations[i], gpu::Usage::TransferDst);
            }
        },
        [copySources, copyDestinations](VkCommandBuffer cmd, const gpu::PassResources& res) {
            for (size_t i = 0; i < copySources.size(); ++i) {
                VkBufferCopy region{0, 0, res.bufferSize(copySources[i])};
                vkCmdCopyBuffer(cmd, res.buffer(copySources[i]), res.buffer(copyDestinations[i]), 1, &region);
            }
        });
}

}  // namespace obscura::passes
