#include "vk_descriptors.h"

#include "vk_util.h"

#include <iterator>

namespace cavity::gpu::vk {

namespace {
constexpr uint32_t kSetsPerPool = 256;
constexpr uint32_t kDescriptorsPerType = 1024;
}  // namespace

DescriptorPools::~DescriptorPools() {
    for (VkDescriptorPool p : pools_) vkDestroyDescriptorPool(d_.device, p, nullptr);
}

Status DescriptorPools::reset() {
    for (VkDescriptorPool p : pools_) CAVITY_VK(vkResetDescriptorPool(d_.device, p, 0), "vkResetDescriptorPool");
    current_ = 0;
    return {};
}

Result<VkDescriptorSet> DescriptorPools::allocate(VkDescriptorSetLayout layout, const std::string& who) {
    for (;;) {
        const bool fresh = current_ == pools_.size();
        if (fresh) {
            const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kDescriptorsPerType},
                                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kDescriptorsPerType},
                                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kDescriptorsPerType},
                                                  {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kDescriptorsPerType}};
            auto ci = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
            ci.maxSets = kSetsPerPool;
            ci.poolSizeCount = uint32_t(std::size(sizes));
            ci.pPoolSizes = sizes;
            VkDescriptorPool p = VK_NULL_HANDLE;
            CAVITY_VK(vkCreateDescriptorPool(d_.device, &ci, nullptr, &p), "vkCreateDescriptorPool for " + who);
            pools_.push_back(p);
        }
        auto ai = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
        ai.descriptorPool = pools_[current_];
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &layout;
        VkDescriptorSet set = VK_NULL_HANDLE;
        const VkResult r = vkAllocateDescriptorSets(d_.device, &ai, &set);
        if (r == VK_SUCCESS) return set;
        // A full pool: move on to the next one (made above if needed). A fresh
        // pool that cannot hold one set means the set itself is too large.
        const bool full = r == VK_ERROR_OUT_OF_POOL_MEMORY || r == VK_ERROR_FRAGMENTED_POOL;
        if (!full || fresh) return vkError("vkAllocateDescriptorSets for " + who, r);
        ++current_;
    }
}

}  // namespace cavity::gpu::vk
