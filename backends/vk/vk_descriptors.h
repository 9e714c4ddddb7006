// Descriptor sets for one frame's dispatches and draws. Frames are recorded,
// submitted and waited for one at a time, so every set is reset at the next
// beginFrame.
#pragma once

#include "result.h"
#include "vk_device.h"

#include <string>
#include <vector>

namespace cavity::gpu::vk {

class DescriptorPools {
public:
    explicit DescriptorPools(Device& d) : d_(d) {}
    ~DescriptorPools();
    DescriptorPools(const DescriptorPools&) = delete;
    DescriptorPools& operator=(const DescriptorPools&) = delete;

    Status reset();   // after the frame that used the sets has completed
    Result<VkDescriptorSet> allocate(VkDescriptorSetLayout layout, const std::string& who);

private:
    Device& d_;
    std::vector<VkDescriptorPool> pools_;   // grows when a frame outgrows them
    size_t current_ = 0;
};

}  // namespace cavity::gpu::vk
