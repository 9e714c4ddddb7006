// The backend's formats in Vulkan terms, and the conversions between the
// interface's float pixels and each format's texels.
#pragma once

#include "backend.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace cavity::gpu::vk {

VkFormat toVkFormat(Format f);
inline bool isDepth(Format f) { return f == Format::D32; }
inline VkImageAspectFlags aspectOf(Format f) {
    return isDepth(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

// channelCount(f) floats per pixel <-> tightly packed texels of f (the
// conversions: backends/texels/texels.h).
// `in.size()` and `out.size()` are in floats.
void packTexels(Format f, std::span<const float> in, std::byte* out);
void unpackTexels(Format f, const std::byte* in, std::span<float> out);

}  // namespace cavity::gpu::vk
