#include "vk_backend.h"

#include "vk_util.h"

#include <cstring>
#include <utility>

namespace cavity::gpu {

Result<std::unique_ptr<Backend>> createVkBackend(const BackendOptions& options) {
    CAVITY_ASSIGN(auto device, vk::createDevice(options));
    auto backend = std::make_unique<vk::VulkanBackend>(std::move(device));
    CAVITY_TRY(backend->init());
    return std::unique_ptr<Backend>(std::move(backend));
}

}  // namespace cavity::gpu

namespace cavity::gpu::vk {

VulkanBackend::VulkanBackend(std::unique_ptr<Device> device)
    : d_(std::move(device)), descriptors_(*d_), timestamps_(*d_) {}

Status VulkanBackend::init() {
    auto pool = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = d_->queueFamily;
    CAVITY_VK(vkCreateCommandPool(d_->device, &pool, nullptr, &framePool_), "vkCreateCommandPool (frames)");
    auto cb = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    cb.commandPool = framePool_;
    cb.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cb.commandBufferCount = 1;
    CAVITY_VK(vkAllocateCommandBuffers(d_->device, &cb, &frameCmd_), "vkAllocateCommandBuffers (frames)");
    auto fence = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    CAVITY_VK(vkCreateFence(d_->device, &fence, nullptr, &frameFence_), "vkCreateFence (frames)");
    return {};
}

VulkanBackend::~VulkanBackend() {
    vkDeviceWaitIdle(d_->device);
    for (auto& [id, p] : pipelines_) destroyPipeline(*d_, p);
    for (auto& [id, i] : images_) destroyImage(*d_, i);
    for (auto& [id, b] : buffers_) destroyBuffer(*d_, b);
    samplers_.destroy(*d_);
    if (frameFence_) vkDestroyFence(d_->device, frameFence_, nullptr);
    if (framePool_) vkDestroyCommandPool(d_->device, framePool_, nullptr);
    // descriptors_ and timestamps_ go next, then the device and instance.
}

const ImageRes* VulkanBackend::findImage(Image i) const {
    auto it = images_.find(i.id);
    return it == images_.end() ? nullptr : &it->second;
}

Result<Image> VulkanBackend::createImage(const ImageDesc& desc) {
    CAVITY_ASSIGN(ImageRes img, vk::createImage(*d_, desc));
    images_.emplace(nextId_, std::move(img));
    return Image{nextId_++};
}

Result<Buffer> VulkanBackend::createBuffer(const BufferDesc& desc) {
    CAVITY_ASSIGN(BufferRes buf, vk::createBuffer(*d_, desc));
    buffers_.emplace(nextId_, std::move(buf));
    return Buffer{nextId_++};
}

Result<Pipeline> VulkanBackend::createComputePipeline(const ComputePipelineDesc& desc) {
    CAVITY_ASSIGN(PipelineRes p, vk::createComputePipeline(*d_, desc));
    pipelines_.emplace(nextId_, std::move(p));
    return Pipeline{nextId_++};
}

Result<Pipeline> VulkanBackend::createGraphicsPipeline(const GraphicsPipelineDesc& desc) {
    CAVITY_ASSIGN(PipelineRes p, vk::createGraphicsPipeline(*d_, desc));
    pipelines_.emplace(nextId_, std::move(p));
    return Pipeline{nextId_++};
}

PipelineInfo VulkanBackend::pipelineInfo(Pipeline p) const {
    PipelineInfo info;
    if (auto it = pipelines_.find(p.id); it != pipelines_.end()) {
        info.stats = it->second.stats;
        info.statsReason = it->second.statsReason;
    }
    return info;
}

// Unknown or null handles are ignored, so that cleanup paths need no checks.
void VulkanBackend::destroy(Image i) {
    if (recording_) return deadImages_.push_back(i);
    if (auto it = images_.find(i.id); it != images_.end()) {
        destroyImage(*d_, it->second);
        images_.erase(it);
    }
}

void VulkanBackend::destroy(Buffer b) {
    if (recording_) return deadBuffers_.push_back(b);
    if (auto it = buffers_.find(b.id); it != buffers_.end()) {
        destroyBuffer(*d_, it->second);
        buffers_.erase(it);
    }
}

void VulkanBackend::destroy(Pipeline p) {
    if (recording_) return deadPipelines_.push_back(p);
    if (auto it = pipelines_.find(p.id); it != pipelines_.end()) {
        destroyPipeline(*d_, it->second);
        pipelines_.erase(it);
    }
}

void VulkanBackend::destroyDeferred() {
    for (Image i : std::exchange(deadImages_, {})) destroy(i);
    for (Buffer b : std::exchange(deadBuffers_, {})) destroy(b);
    for (Pipeline p : std::exchange(deadPipelines_, {})) destroy(p);
}

Status VulkanBackend::uploadImage(Image i, int mipLevel, std::span<const float> pixels) {
    const ImageRes* img = findImage(i);
    if (!img) return badInput("uploadImage: no image " + std::to_string(i.id));
    return vk::uploadImage(*d_, *img, mipLevel, pixels);
}

Result<std::vector<float>> VulkanBackend::readImage(Image i, int mipLevel) {
    const ImageRes* img = findImage(i);
    if (!img) return badInput("readImage: no image " + std::to_string(i.id));
    return vk::readImage(*d_, *img, mipLevel);
}

Status VulkanBackend::updateBuffer(Buffer b, std::span<const std::byte> data, size_t offset) {
    auto it = buffers_.find(b.id);
    if (it == buffers_.end()) return badInput("updateBuffer: no buffer " + std::to_string(b.id));
    const BufferRes& buf = it->second;
    if (offset > buf.desc.size || data.size() > buf.desc.size - offset)
        return badInput("updateBuffer '" + buf.desc.label + "': " + std::to_string(data.size()) + " bytes at " +
                        std::to_string(offset) + " overrun its " + std::to_string(buf.desc.size));
    // Coherent memory: the next vkQueueSubmit makes the write visible.
    std::memcpy(buf.mapped + offset, data.data(), data.size());
    return {};
}

Status VulkanBackend::finish() {
    CAVITY_VK(vkQueueWaitIdle(d_->queue), "vkQueueWaitIdle");
    return {};
}

}  // namespace cavity::gpu::vk
