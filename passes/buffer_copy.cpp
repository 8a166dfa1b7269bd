#include "passes/buffer_copy.h"

#include "gpu/vulkan_functions.h"

namespace obscura::passes {

gpu::BufferHandle addBufferCopyPass(gpu::FrameGraph& graph, const std::string& name, gpu::BufferHandle source,
                                    gpu::BufferHandle destination, VkDeviceSize bytes) {
    gpu::BufferHandle written;
    graph.addPass(
        name, gpu::PassKind::Transfer,
        [&](gpu::FrameGraph::PassBuilder& pass) {
            pass.read(source, gpu::Usage::TransferSrc);
            written = pass.write(destination, gpu::Usage::TransferDst);
        },
        [source, destination, bytes](VkCommandBuffer cmd, const gpu::PassResources& res) {
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(cmd, res.buffer(source), res.buffer(destination), 1, &region);
        });
    return written;
}

}  // namespace obscura::passes
