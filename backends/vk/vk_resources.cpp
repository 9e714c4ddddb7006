#include "vk_resources.h"

#include "vk_formats.h"
#include "vk_util.h"

#include <bit>
#include <cstdio>

namespace cavity::gpu::vk {

namespace {

// Tries the memory types that have required|preferred first, then those with
// just `required`: a full heap of the preferred kind (NVIDIA's 256 MiB
// device-local host-visible window) falls back instead of failing.
Status allocate(Device& d, const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                VkMemoryPropertyFlags preferred, VkDeviceMemory& out, const std::string& who) {
    VkResult last = VK_SUCCESS;
    for (const VkMemoryPropertyFlags want : {required | preferred, required}) {
        for (uint32_t i = 0; i < d.memory.memoryTypeCount; ++i) {
            if (!(req.memoryTypeBits & (1u << i)) || (d.memory.memoryTypes[i].propertyFlags & want) != want)
                continue;
            auto ai = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
            ai.allocationSize = req.size;
            ai.memoryTypeIndex = i;
            last = vkAllocateMemory(d.device, &ai, nullptr, &out);
            if (last == VK_SUCCESS) return {};
        }
        if (!preferred) break;
    }
    if (last == VK_SUCCESS) {
        char flags[16];
        std::snprintf(flags, sizeof flags, "0x%x", unsigned(required));
        return internal("vkAllocateMemory " + std::to_string(req.size) + " bytes for " + who +
                        ": no memory type has the property flags " + flags);
    }
    return vkError("vkAllocateMemory " + std::to_string(req.size) + " bytes for " + who, last);
}

Status initBuffer(Device& d, BufferRes& b, VkBufferUsageFlags usage, VkMemoryPropertyFlags preferred) {
    const std::string who = std::to_string(b.desc.size) + " bytes '" + b.desc.label + "'";
    auto ci = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    ci.size = b.desc.size;
    ci.usage = usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    CAVITY_VK(vkCreateBuffer(d.device, &ci, nullptr, &b.buffer), "vkCreateBuffer " + who);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(d.device, b.buffer, &req);
    CAVITY_TRY(allocate(d, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                        preferred, b.memory, who));
    CAVITY_VK(vkBindBufferMemory(d.device, b.buffer, b.memory, 0), "vkBindBufferMemory " + who);
    void* p = nullptr;
    CAVITY_VK(vkMapMemory(d.device, b.memory, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory " + who);
    b.mapped = static_cast<std::byte*>(p);
    return {};
}

Result<BufferRes> hostBuffer(Device& d, size_t size, VkBufferUsageFlags usage, VkMemoryPropertyFlags preferred,
                             std::string label) {
    BufferRes b;
    b.desc = {size, BufferUsage::Storage, std::move(label)};
    if (Status s = initBuffer(d, b, usage, preferred); !s) {
        destroyBuffer(d, b);
        return s.error();
    }
    return b;
}

Status createView(Device& d, const ImageRes& img, int first, int levels, VkImageView& out) {
    auto ci = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    ci.image = img.image;
    ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    ci.format = toVkFormat(img.desc.format);
    ci.subresourceRange = {aspectOf(img.desc.format), uint32_t(first), uint32_t(levels), 0, 1};
    CAVITY_VK(vkCreateImageView(d.device, &ci, nullptr, &out),
              "vkCreateImageView " + img.describe() + " levels " + std::to_string(first) + ".." +
                  std::to_string(first + levels - 1));
    return {};
}

// The size and level count against what the device and the image allow.
Status checkImageSize(const Device& d, const ImageRes& img) {
    const ImageDesc& desc = img.desc;
    const uint32_t maxDim = d.props.limits.maxImageDimension2D;
    if (desc.width <= 0 || desc.height <= 0 || uint32_t(desc.width) > maxDim || uint32_t(desc.height) > maxDim)
        return badInput("createImage " + img.describe() + ": size must be 1.." + std::to_string(maxDim));
    const int maxLevels = std::bit_width(unsigned(std::max(desc.width, desc.height)));
    if (img.levels < 1 || img.levels > maxLevels)
        return badInput("createImage " + img.describe() + ": " + std::to_string(desc.mipLevels) +
                        " mip levels, at most " + std::to_string(maxLevels));
    return {};
}

// Usage is what the description asks for (every use by default) that the
// format's features allow on this device: e.g. R8 storage is optional in
// Vulkan. By default a missing use fails at the dispatch or draw that
// needs it, naming the image; one asked for fails here. TRANSFER_DST is
// always there for clearToGeneral's clear.
Status chooseUsage(const Device& d, ImageRes& img) {
    const ImageDesc& desc = img.desc;
    const VkFormat format = toVkFormat(desc.format);
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(d.physical, format, &fp);
    const VkFormatFeatureFlags f = fp.optimalTilingFeatures;
    const uint32_t want = desc.usage ? desc.usage : ~0u;
    if ((want & ImageSampled) && !(f & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT))
        return internal("createImage " + img.describe() + ": the device cannot sample this format");
    img.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (want & ImageSampled) img.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (want & ImageTransfer) img.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const struct {
        ImageUsage use;
        VkFormatFeatureFlags feature;
        VkImageUsageFlags flag;
        const char* what;
    } optional[] = {
        {ImageStorage, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT, VK_IMAGE_USAGE_STORAGE_BIT, "storage image"},
        {ImageColorTarget, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "colour target"},
        {ImageDepthTarget, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
         "depth target"},
    };
    for (const auto& o : optional) {
        if (!(want & o.use)) continue;
        if (f & o.feature) img.usage |= o.flag;
        else if (desc.usage)
            return internal("createImage " + img.describe() + ": '" + d.props.deviceName + "' cannot use " +
                            formatName(desc.format) + " as a " + o.what);
    }
    return {};
}

// The image at img.usage, its device-local memory, and its views (the whole
// chain and each level).
Status createImageAndViews(Device& d, ImageRes& img) {
    const ImageDesc& desc = img.desc;
    const VkFormat format = toVkFormat(desc.format);
    auto ci = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {uint32_t(desc.width), uint32_t(desc.height), 1};
    ci.mipLevels = uint32_t(img.levels);
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = img.usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    CAVITY_VK(vkCreateImage(d.device, &ci, nullptr, &img.image), "vkCreateImage " + img.describe());
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d.device, img.image, &req);
    CAVITY_TRY(allocate(d, req, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, img.memory, img.describe()));
    CAVITY_VK(vkBindImageMemory(d.device, img.image, img.memory, 0), "vkBindImageMemory " + img.describe());
    CAVITY_TRY(createView(d, img, 0, img.levels, img.view));
    if (img.levels == 1) {
        img.levelViews = {img.view};
    } else {
        // A storage descriptor names exactly one level; one view per level.
        img.levelViews.assign(size_t(img.levels), VK_NULL_HANDLE);
        for (int l = 0; l < img.levels; ++l) CAVITY_TRY(createView(d, img, l, 1, img.levelViews[size_t(l)]));
    }
    return {};
}

// The image's one and only layout change. GENERAL stays for every use:
// compute passes store to images that later passes sample, and GENERAL is
// the layout for storage. Colour targets of fragment passes could go to
// COLOR_ATTACHMENT_OPTIMAL and then SHADER_READ_ONLY_OPTIMAL, which lets a
// driver compress them; that takes per-image, per-level layout tracking
// through frames, uploads and readbacks, and is left until a GPU run
// shows it pays (lavapipe has no compression to show it).
Status clearToGeneral(Device& d, const ImageRes& img) {
    const ImageDesc& desc = img.desc;
    return d.submitOnce("creating " + img.describe(), [&](VkCommandBuffer cmd) {
        const VkImageSubresourceRange all{aspectOf(desc.format), 0, uint32_t(img.levels), 0, 1};
        auto b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img.image;
        b.subresourceRange = all;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr,
                             0, nullptr, 1, &b);
        if (isDepth(desc.format)) {
            const VkClearDepthStencilValue zero{0.0f, 0};
            vkCmdClearDepthStencilImage(cmd, img.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
        } else {
            const VkClearColorValue zero{};
            vkCmdClearColorImage(cmd, img.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
        }
    });
}

Status initImage(Device& d, ImageRes& img) {
    CAVITY_TRY(checkImageSize(d, img));
    CAVITY_TRY(chooseUsage(d, img));
    CAVITY_TRY(createImageAndViews(d, img));
    return clearToGeneral(d, img);
}

Status checkLevel(const ImageRes& img, int level, const char* op) {
    if (level < 0 || level >= img.levels)
        return badInput(std::string(op) + " " + img.describe() + ": no mip level " + std::to_string(level) +
                        " (it has " + std::to_string(img.levels) + ")");
    return {};
}

VkBufferImageCopy copyRegion(const ImageRes& img, int level) {
    VkBufferImageCopy r{};
    r.imageSubresource = {aspectOf(img.desc.format), uint32_t(level), 0, 1};
    r.imageExtent = {uint32_t(img.width(level)), uint32_t(img.height(level)), 1};
    return r;   // buffer offset 0, rows tightly packed, row 0 first
}

// Between calls every image is in GENERAL, but a copy runs in the transfer
// layout: the validation layer reports GENERAL copies as a performance
// warning, and tests fail on any warning. Only this one-off submission sees
// the other layout.
void copyLayout(VkCommandBuffer cmd, const ImageRes& img, int level, VkImageLayout from, VkImageLayout to) {
    auto b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img.image;
    b.subresourceRange = {aspectOf(img.desc.format), uint32_t(level), 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
}

}  // namespace

std::string ImageRes::describe() const {
    return std::to_string(desc.width) + "x" + std::to_string(desc.height) + " " + formatName(desc.format) + " '" +
           desc.label + "'";
}

Result<ImageRes> createImage(Device& d, const ImageDesc& desc) {
    ImageRes img;
    img.desc = desc;
    img.levels = std::max(1, desc.mipLevels);
    if (Status s = initImage(d, img); !s) {
        destroyImage(d, img);
        return s.error();
    }
    return img;
}

void destroyImage(Device& d, ImageRes& img) {
    for (VkImageView v : img.levelViews)
        if (v && v != img.view) vkDestroyImageView(d.device, v, nullptr);
    if (img.view) vkDestroyImageView(d.device, img.view, nullptr);
    if (img.image) vkDestroyImage(d.device, img.image, nullptr);
    if (img.memory) vkFreeMemory(d.device, img.memory, nullptr);
    img = ImageRes{};
}

Status uploadImage(Device& d, const ImageRes& img, int level, std::span<const float> pixels) {
    if (auto why = missingUsage(img.desc, ImageTransfer); !why.empty()) return badInput("uploadImage: " + why);
    CAVITY_TRY(checkLevel(img, level, "uploadImage"));
    const size_t texels = size_t(img.width(level)) * size_t(img.height(level));
    const size_t floats = texels * size_t(channelCount(img.desc.format));
    if (pixels.size() != floats)
        return badInput("uploadImage " + img.describe() + " level " + std::to_string(level) + ": got " +
                        std::to_string(pixels.size()) + " floats, need " + std::to_string(floats));
    CAVITY_ASSIGN(BufferRes staging, hostBuffer(d, texels * size_t(bytesPerPixel(img.desc.format)),
                                                VK_BUFFER_USAGE_TRANSFER_SRC_BIT, 0, "upload of " + img.desc.label));
    packTexels(img.desc.format, pixels, staging.mapped);
    const VkBufferImageCopy region = copyRegion(img, level);
    Status s = d.submitOnce("upload to " + img.describe(), [&](VkCommandBuffer cmd) {
        copyLayout(cmd, img, level, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        copyLayout(cmd, img, level, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    });
    destroyBuffer(d, staging);
    return s;
}

Result<std::vector<float>> readImage(Device& d, const ImageRes& img, int level) {
    if (auto why = missingUsage(img.desc, ImageTransfer); !why.empty()) return badInput("readImage: " + why);
    CAVITY_TRY(checkLevel(img, level, "readImage"));
    const size_t texels = size_t(img.width(level)) * size_t(img.height(level));
    // Cached memory makes the host's reads of the copy fast where it exists.
    CAVITY_ASSIGN(BufferRes staging,
                  hostBuffer(d, texels * size_t(bytesPerPixel(img.desc.format)), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             VK_MEMORY_PROPERTY_HOST_CACHED_BIT, "readback of " + img.desc.label));
    const VkBufferImageCopy region = copyRegion(img, level);
    Status s = d.submitOnce("readback of " + img.describe(), [&](VkCommandBuffer cmd) {
        copyLayout(cmd, img, level, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
        copyLayout(cmd, img, level, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    });
    std::vector<float> out;
    if (s) {
        out.resize(texels * size_t(channelCount(img.desc.format)));
        unpackTexels(img.desc.format, staging.mapped, out);
    }
    destroyBuffer(d, staging);
    if (!s) return s.error();
    return out;
}

Result<BufferRes> createBuffer(Device& d, const BufferDesc& desc) {
    if (desc.size == 0) return badInput("createBuffer '" + desc.label + "': size 0");
    BufferRes b;
    b.desc = desc;
    const VkBufferUsageFlags usage =
        (desc.usage == BufferUsage::Uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) |
        VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    // Kernels read these every invocation; device-local host-visible memory
    // (resizable BAR) keeps those reads off the PCIe bus where it exists.
    if (Status s = initBuffer(d, b, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT); !s) {
        destroyBuffer(d, b);
        return s.error();
    }
    return b;
}

void destroyBuffer(Device& d, BufferRes& b) {
    if (b.buffer) vkDestroyBuffer(d.device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(d.device, b.memory, nullptr);   // also unmaps
    b = BufferRes{};
}

Result<VkSampler> SamplerCache::get(Device& d, const SamplerState& s) {
    const size_t key = size_t(s.filter == Filter::Linear) | size_t(s.address == Address::Repeat) << 1 |
                       size_t(s.mipmaps) << 2;
    if (samplers_[key]) return samplers_[key];
    const VkFilter filter = s.filter == Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    const VkSamplerAddressMode address =
        s.address == Address::Repeat ? VK_SAMPLER_ADDRESS_MODE_REPEAT : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    auto ci = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    ci.magFilter = ci.minFilter = filter;
    // Without mipmaps, maxLod 0 pins sampling to level 0 whatever the view holds.
    ci.mipmapMode = s.mipmaps ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    ci.addressModeU = ci.addressModeV = ci.addressModeW = address;
    ci.maxLod = s.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
    ci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    CAVITY_VK(vkCreateSampler(d.device, &ci, nullptr, &samplers_[key]),
              std::string("vkCreateSampler ") + (s.filter == Filter::Linear ? "linear" : "nearest") + " " +
                  (s.address == Address::Repeat ? "repeat" : "clamp") + (s.mipmaps ? " mipmapped" : ""));
    return samplers_[key];
}

void SamplerCache::destroy(Device& d) {
    for (auto& s : samplers_) {
        if (s) vkDestroySampler(d.device, s, nullptr);
        s = VK_NULL_HANDLE;
    }
}

}  // namespace cavity::gpu::vk
