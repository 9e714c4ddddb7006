// Images, buffers and samplers: creation, destruction, upload and readback.
// One device-memory allocation per resource; the harness creates a few dozen.
#pragma once

#include "backend.h"
#include "vk_device.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace cavity::gpu::vk {

struct ImageRes {
    ImageDesc desc;
    int levels = 1;
    VkImageUsageFlags usage = 0;   // what desc.usage asks for and the format allows on this device (see createImage)
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;        // every level, for sampling
    // levelViews[k]: level k alone, for storage writes to that level and (k = 0)
    // attachments. With one level, levelViews[0] == view.
    std::vector<VkImageView> levelViews;

    int width(int level = 0) const { return std::max(1, desc.width >> level); }
    int height(int level = 0) const { return std::max(1, desc.height >> level); }
    std::string describe() const;   // "1920x1080 RGBA16F 'ao'"
};

struct BufferRes {
    BufferDesc desc;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    std::byte* mapped = nullptr;   // host-visible and coherent, mapped for life
};

// The image is in VK_IMAGE_LAYOUT_GENERAL with every texel zero on return,
// so that a kernel reading a never-written image gives the same result on
// every backend and run.
Result<ImageRes> createImage(Device& d, const ImageDesc& desc);
void destroyImage(Device& d, ImageRes& img);
Status uploadImage(Device& d, const ImageRes& img, int level, std::span<const float> pixels);
Result<std::vector<float>> readImage(Device& d, const ImageRes& img, int level);

Result<BufferRes> createBuffer(Device& d, const BufferDesc& desc);
void destroyBuffer(Device& d, BufferRes& buf);

// One VkSampler per distinct SamplerState, made on first use.
class SamplerCache {
public:
    Result<VkSampler> get(Device& d, const SamplerState& s);
    void destroy(Device& d);

private:
    std::array<VkSampler, 8> samplers_{};
};

}  // namespace cavity::gpu::vk
