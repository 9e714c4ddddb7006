#include "vk_barriers.h"

#include "vk_util.h"

namespace cavity::gpu::vk {

void BarrierTracker::barrier() {
    // Two barrier() calls with nothing between them are one barrier.
    if (!since_.stages) return;
    source_ = since_;
    since_ = {};
    covered_ = {};
}

void BarrierTracker::before(Device& d, VkCommandBuffer cmd, const SyncScope& dst) {
    if (d.noBarriers || !source_.stages || covered_.covers(dst)) return;
    pipelineBarrier(d, cmd, source_, dst);
    covered_ |= dst;
}

namespace {

// synchronization2's split shader reads and writes; the other bits we use
// have the same values in both APIs.
VkAccessFlags toAccess1(VkAccessFlags2 a) {
    VkAccessFlags out = VkAccessFlags(a & 0xffffffffu);
    if (a & (VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT)) out |= VK_ACCESS_SHADER_READ_BIT;
    if (a & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) out |= VK_ACCESS_SHADER_WRITE_BIT;
    return out;
}

}  // namespace

void pipelineBarrier(Device& d, VkCommandBuffer cmd, const SyncScope& narrowSrc, const SyncScope& narrowDst) {
    // BackendOptions::fullBarriers: the widest dependency instead.
    const SyncScope src = d.fullBarriers ? SyncScope{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT} : narrowSrc;
    const SyncScope dst = d.fullBarriers ? SyncScope{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT}
                                         : narrowDst;
    if (d.cmdPipelineBarrier2) {
        auto b = vkStruct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
        b.srcStageMask = src.stages;
        b.srcAccessMask = src.access;
        b.dstStageMask = dst.stages;
        b.dstAccessMask = src.access ? dst.access : 0;
        auto info = vkStruct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
        info.memoryBarrierCount = 1;
        info.pMemoryBarriers = &b;
        d.cmdPipelineBarrier2(cmd, &info);
        return;
    }
    // Only reads before it: an execution dependency is all a write after a read needs.
    auto b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = toAccess1(src.access);
    b.dstAccessMask = toAccess1(dst.access);
    vkCmdPipelineBarrier(cmd, VkPipelineStageFlags(src.stages), VkPipelineStageFlags(dst.stages), 0,
                         src.access ? 1 : 0, &b, 0, nullptr, 0, nullptr);
}

}  // namespace cavity::gpu::vk
