#include "gpu/timestamps.h"

#include "gpu/vk_check.h"

namespace obscura::gpu {

Timestamps::Timestamps(Device& device, uint32_t maxPasses) : device_(device), capacity_(maxPasses) {
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    ci.queryCount = 2 * maxPasses;
    vkCheck(vkCreateQueryPool(device_.vk(), &ci, nullptr, &pool_), "vkCreateQueryPool");
    periodNs_ = device_.context().properties().limits.timestampPeriod;
}

Timestamps::~Timestamps() {
    VkDevice d = device_.vk();
    VkQueryPool p = pool_;
    device_.retire([d, p] { vkDestroyQueryPool(d, p, nullptr); });
}

void Timestamps::reset(VkCommandBuffer cmd) {
    names_.clear();
    vkCmdResetQueryPool(cmd, pool_, 0, 2 * capacity_);
}

void Timestamps::begin(VkCommandBuffer cmd, const std::string& pass) {
    if (names_.size() >= capacity_) return;
    names_.push_back(pass);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(2 * (names_.size() - 1)));
}

void Timestamps::end(VkCommandBuffer cmd) {
    if (names_.empty() || names_.size() > capacity_) return;
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(2 * (names_.size() - 1) + 1));
}

std::vector<PassTime> Timestamps::resolve() {
    std::vector<PassTime> out;
    if (names_.empty()) return out;
    std::vector<uint64_t> ticks(2 * names_.size());
    vkCheck(vkGetQueryPoolResults(device_.vk(), pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                                  ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults");
    for (size_t i = 0; i < names_.size(); ++i) {
        double ms = double(ticks[2 * i + 1] - ticks[2 * i]) * periodNs_ * 1e-6;
        out.push_back({names_[i], ms});
    }
    return out;
}

}  // namespace obscura::gpu
