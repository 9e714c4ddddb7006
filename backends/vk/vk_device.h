// The Vulkan instance, the one physical device and queue the backend uses,
// and what the rest of the backend needs to know about them.
#pragma once

#include "backend.h"

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace cavity::gpu::vk {

struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroyMessenger = nullptr;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    uint32_t timestampValidBits = 0;
    VkPhysicalDeviceProperties props{};
    VkPhysicalDeviceMemoryProperties memory{};
    // Core 1.3 entry points, or the VK_KHR_dynamic_rendering ones on 1.2.
    PFN_vkCmdBeginRendering cmdBeginRendering = nullptr;
    PFN_vkCmdEndRendering cmdEndRendering = nullptr;
    // synchronization2 (core 1.3, where the device enables the feature);
    // null: barriers go through vkCmdPipelineBarrier.
    PFN_vkCmdPipelineBarrier2 cmdPipelineBarrier2 = nullptr;
    // VK_KHR_pipeline_executable_properties, enabled where the device has
    // it (null otherwise): each pipeline's compiled statistics.
    PFN_vkGetPipelineExecutablePropertiesKHR getExecutableProperties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR getExecutableStatistics = nullptr;
    bool fullBarriers = false;   // BackendOptions::fullBarriers
    bool noBarriers = false;     // BackendOptions::noBarriers
    DeviceInfo info;

    // For submitOnce.
    VkCommandPool oncePool = VK_NULL_HANDLE;
    VkCommandBuffer onceCmd = VK_NULL_HANDLE;
    VkFence onceFence = VK_NULL_HANDLE;

    Device() = default;
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;
    ~Device();

    // Records `record` into a one-off command buffer, submits it and waits.
    // Full barriers before and after order it against the frames submitted
    // before and after, and make its writes visible to the host.
    Status submitOnce(const std::string& what, const std::function<void(VkCommandBuffer)>& record);

    // Validation messages; the messenger may call from any thread.
    void addMessage(std::string m);
    std::vector<std::string> takeMessages();

private:
    std::mutex messagesMutex_;
    std::vector<std::string> messages_;
};

// Instance, device selection (BackendOptions::deviceName / deviceIndex),
// logical device and queue. Fails with BackendUnavailable naming what was
// found when no usable device exists.
Result<std::unique_ptr<Device>> createDevice(const BackendOptions& options);

// A global memory dependency: every earlier write is available and visible to
// every later command. What brackets submitOnce; barrier() is narrower
// (vk_barriers.h).
void fullBarrier(VkCommandBuffer cmd);

}  // namespace cavity::gpu::vk
