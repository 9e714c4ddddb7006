// Small helpers for every Vulkan file. Every Vulkan call is checked; a failure
// becomes an Internal error that says what was attempted and with what, e.g.
//   "vkCreateImage 1920x1080 RGBA16F 'ao': VK_ERROR_OUT_OF_DEVICE_MEMORY".
#pragma once

#include "result.h"

#include <vulkan/vulkan.h>

#include <string>

namespace cavity::gpu::vk {

std::string vkResultName(VkResult r);   // "VK_ERROR_DEVICE_LOST"
std::string versionString(uint32_t v);  // "1.3.230"

// A Vulkan struct with sType and pNext set and every other member zero.
// (`T x{sType}` means the same but trips -Wmissing-field-initializers.)
template <class T>
T vkStruct(VkStructureType type, void* next = nullptr) {
    T s{};
    s.sType = type;
    s.pNext = next;
    return s;
}

inline Error vkError(const std::string& what, VkResult r) {
    return internal(what + ": " + vkResultName(r));
}

}  // namespace cavity::gpu::vk

// Returns the error from the enclosing function when `call` fails. `what` is
// only evaluated on failure, so message building costs nothing on success.
#define CAVITY_VK(call, what)                                              \
    do {                                                                   \
        const VkResult cavity_vk_r_ = (call);                              \
        if (cavity_vk_r_ != VK_SUCCESS)                                    \
            return ::cavity::gpu::vk::vkError((what), cavity_vk_r_);       \
    } while (0)
