// barrier() as narrow as what was recorded. The passes since the last
// barrier() leave a source scope (the stages they ran in and what they
// wrote); barrier() only takes note of it, and the dependency is recorded
// before the next command, whose stages and accesses are then known. Every
// command until the next barrier() is covered, so a compute pass followed
// by a draw that both read what came before each get what they need.
#pragma once

#include "vk_device.h"

namespace cavity::gpu::vk {

// Stages and accesses in synchronization2's terms; on a device without it
// they are translated to vkCmdPipelineBarrier's.
struct SyncScope {
    VkPipelineStageFlags2 stages = 0;
    VkAccessFlags2 access = 0;
    SyncScope& operator|=(const SyncScope& o) {
        stages |= o.stages;
        access |= o.access;
        return *this;
    }
    bool covers(const SyncScope& o) const { return !(o.stages & ~stages) && !(o.access & ~access); }
};

class BarrierTracker {
public:
    // A command was recorded: it ran in `stages` and wrote `writes`.
    void recorded(VkPipelineStageFlags2 stages, VkAccessFlags2 writes) { since_ |= {stages, writes}; }
    void barrier();
    // Records what the last barrier() owes a command that runs in `dst`.
    void before(Device& d, VkCommandBuffer cmd, const SyncScope& dst);
    // A frame starts: the previous one completed behind its fence.
    void reset() { *this = BarrierTracker{}; }

private:
    SyncScope since_;     // recorded since the last barrier()
    SyncScope source_;    // what the last barrier() orders
    SyncScope covered_;   // the commands after it that a dependency already reaches
};

void pipelineBarrier(Device& d, VkCommandBuffer cmd, const SyncScope& src, const SyncScope& dst);

}  // namespace cavity::gpu::vk
