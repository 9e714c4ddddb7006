#include "timestamps.h"

#include "vk_util.h"

#include <algorithm>

namespace cavity::gpu::vk {

namespace {
constexpr uint32_t kPoolSize = 256;
}

Timestamps::~Timestamps() {
    for (VkQueryPool p : pools_) vkDestroyQueryPool(d_.device, p, nullptr);
}

void Timestamps::beginFrame() {
    used_ = 0;
    scopes_.clear();
    open_.clear();
    times_.clear();
}

Result<uint32_t> Timestamps::writeTimestamp(VkCommandBuffer cmd) {
    const uint32_t pool = used_ / kPoolSize, query = used_ % kPoolSize;
    if (pool == pools_.size()) {
        // Creating a pool while recording is allowed; it is reset below,
        // inside the command buffer, before its first query.
        auto ci = vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
        ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
        ci.queryCount = kPoolSize;
        VkQueryPool p = VK_NULL_HANDLE;
        CAVITY_VK(vkCreateQueryPool(d_.device, &ci, nullptr, &p),
                  "vkCreateQueryPool " + std::to_string(kPoolSize) + " timestamps");
        pools_.push_back(p);
    }
    // Reset on first use in each frame; the reset is ordered before the
    // writes to the same queries by the spec, so no barrier is needed.
    if (query == 0) vkCmdResetQueryPool(cmd, pools_[pool], 0, kPoolSize);
    // BOTTOM_OF_PIPE for both ends: a timestamp is written once every earlier
    // command has finished. The begin timestamp thus marks the end of the
    // previous work (TOP_OF_PIPE would fire as soon as the GPU reaches the
    // command, counting the tail of earlier passes into this scope), and the
    // end timestamp marks the end of this scope's work.
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pools_[pool], query);
    // On a CPU device, an execution barrier after every timestamp: lavapipe
    // takes a timestamp only when the next flush runs, and without it a scope
    // around one dispatch reads a small fraction of the dispatch's time. A GPU
    // writes BOTTOM_OF_PIPE timestamps when earlier work is done, and the
    // harness's barrier() between passes orders the rest; there the extra
    // barrier only adds its drain to every pair (an empty pair read about 3x
    // GL's with it on the H100).
    if (d_.info.softwareRenderer)
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                             nullptr, 0, nullptr, 0, nullptr);
    return used_++;
}

Status Timestamps::beginScope(VkCommandBuffer cmd, const std::string& name) {
    CAVITY_ASSIGN(const uint32_t q, writeTimestamp(cmd));
    open_.push_back(scopes_.size());
    scopes_.push_back({name, q, q});
    return {};
}

Status Timestamps::endScope(VkCommandBuffer cmd) {
    if (open_.empty()) return internal("endScope without a matching beginScope");
    CAVITY_ASSIGN(const uint32_t q, writeTimestamp(cmd));
    scopes_[open_.back()].end = q;
    open_.pop_back();
    return {};
}

Status Timestamps::checkClosed() const {
    if (open_.empty()) return {};
    return internal("endFrame: scope '" + scopes_[open_.back()].name + "' was begun but not ended");
}

Status Timestamps::resolve() {
    std::vector<uint64_t> ticks(used_);
    for (uint32_t first = 0; first < used_; first += kPoolSize) {
        const uint32_t count = std::min(kPoolSize, used_ - first);
        CAVITY_VK(vkGetQueryPoolResults(d_.device, pools_[first / kPoolSize], 0, count, count * sizeof(uint64_t),
                                        ticks.data() + first, sizeof(uint64_t),
                                        VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                  "vkGetQueryPoolResults " + std::to_string(count) + " timestamps");
    }
    // Only timestampValidBits of each value count; the counter may wrap
    // between begin and end, which the masked subtraction absorbs.
    const uint32_t bits = d_.timestampValidBits;
    const uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
    const double nsPerTick = d_.props.limits.timestampPeriod;
    times_.clear();
    for (const auto& s : scopes_) {
        const uint64_t delta = ((ticks[s.end] & mask) - (ticks[s.begin] & mask)) & mask;
        times_.push_back({s.name, double(delta) * nsPerTick * 1e-6});
    }
    return {};
}

}  // namespace cavity::gpu::vk
