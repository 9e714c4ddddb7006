// Frame recording: one primary command buffer per frame, submitted and
// waited for in endFrame. Binding lists are checked against the pipeline's
// layout here, so a wrong binding names itself instead of surfacing as a
// validation-layer message or a device fault.
#include "vk_backend.h"

#include "vk_formats.h"
#include "vk_util.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace cavity::gpu::vk {

namespace {

constexpr VkAccessFlags2 kWrites = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

// What a pipeline's bindings may touch, in `stages`. A storage binding counts
// as read and written: the layout does not say which the shader does.
// Uniform buffers are written by the host only, which vkQueueSubmit orders.
SyncScope shaderScope(const PipelineRes& pipe, VkPipelineStageFlags2 stages) {
    SyncScope s;
    for (const BindingSlot& slot : pipe.slots) {
        if (slot.kind == BindingKind::SampledImage) s.access |= VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
        if (slot.kind == BindingKind::StorageImage || slot.kind == BindingKind::StorageBuffer)
            s.access |= VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    }
    if (s.access) s.stages = stages;
    return s;
}

// What a draw may touch. Bindings are shared by both stages (backend.h); a
// load or clear and the store of an attachment run in its attachment stage.
SyncScope drawScope(const PipelineRes& pipe, bool clear) {
    SyncScope scope = shaderScope(pipe, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    scope |= {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | (clear ? 0 : VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT)};
    if (pipe.depth)
        scope |= {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
    return scope;
}

// The draw itself, inside dynamic rendering over the whole target area.
void recordRendering(const Device& d, VkCommandBuffer cmd, const PipelineRes& pipe,
                     const std::vector<VkRenderingAttachmentInfo>& colors, const VkRenderingAttachmentInfo& depth,
                     int width, int height, int vertexCount) {
    auto rendering = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    rendering.renderArea = {{0, 0}, {uint32_t(width), uint32_t(height)}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = uint32_t(colors.size());
    rendering.pColorAttachments = colors.data();
    rendering.pDepthAttachment = pipe.depth ? &depth : nullptr;
    d.cmdBeginRendering(cmd, &rendering);
    // Viewport y = 0 at row 0 with positive height: NDC y = -1 lands on row 0,
    // the first row in memory, as backend.h promises.
    const VkViewport viewport{0, 0, float(width), float(height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &rendering.renderArea);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe.pipeline);
    vkCmdDraw(cmd, uint32_t(vertexCount), 1, 0, 0);
    d.cmdEndRendering(cmd);
}

}  // namespace

void VulkanBackend::fail(Error e) {
    if (!error_) error_ = std::move(e);
}

bool VulkanBackend::recordable(const char* op) {
    if (!recording_) {
        fail(internal(std::string(op) + " outside beginFrame/endFrame"));
        return false;
    }
    return !error_ && cmdOpen_;
}

void VulkanBackend::beginFrame() {
    if (recording_) return fail(internal("beginFrame: the previous frame was not ended"));
    recording_ = true;
    timestamps_.beginFrame();
    if (error_) return;   // from a call outside any frame; endFrame reports it
    // The previous frame completed in endFrame, so its sets can be recycled.
    if (Status s = descriptors_.reset(); !s) return fail(s.error());
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    const VkResult r = vkBeginCommandBuffer(frameCmd_, &begin);
    if (r != VK_SUCCESS) return fail(vkError("vkBeginCommandBuffer (frame)", r));
    cmdOpen_ = true;
    barriers_.reset();
}

Status VulkanBackend::bindResources(const PipelineRes& pipe, std::span<const Bind> binds, VkPipelineBindPoint point,
                                    const std::string& who) {
    for (const Bind& b : binds) {
        const auto same = [&](const auto& x) { return x.binding == b.binding; };
        if (std::count_if(binds.begin(), binds.end(), same) > 1)
            return internal(who + ": binding " + std::to_string(b.binding) + " is given more than once");
        if (std::none_of(pipe.slots.begin(), pipe.slots.end(), same))
            return internal(who + ": binding " + std::to_string(b.binding) + " is not in the pipeline's layout");
    }
    if (pipe.slots.empty()) return {};

    const size_t n = pipe.slots.size();
    std::vector<VkDescriptorImageInfo> imageInfos(n);
    std::vector<VkDescriptorBufferInfo> bufferInfos(n);
    std::vector<VkWriteDescriptorSet> writes(n, vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET));
    for (size_t i = 0; i < n; ++i) {
        const BindingSlot& s = pipe.slots[i];
        const auto slot = [&] {
            return who + ": binding " + std::to_string(s.binding) + " (" + bindingKindName(s.kind) + ")";
        };
        const auto b = std::find_if(binds.begin(), binds.end(), [&](const Bind& x) { return x.binding == s.binding; });
        if (b == binds.end()) return internal(slot() + " has no resource");
        writes[i].dstBinding = s.binding;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = descriptorType(s.kind);
        if (s.kind == BindingKind::UniformBuffer || s.kind == BindingKind::StorageBuffer) {
            const auto it = buffers_.find(b->buffer.id);
            if (it == buffers_.end()) return internal(slot() + ": no buffer " + std::to_string(b->buffer.id));
            const BufferRes& buf = it->second;
            const bool uniform = s.kind == BindingKind::UniformBuffer;
            if ((buf.desc.usage == BufferUsage::Uniform) != uniform)
                return internal(slot() + ": buffer '" + buf.desc.label + "' was created as a " +
                                (uniform ? "storage" : "uniform") + " buffer");
            const auto& limits = d_->props.limits;
            const VkDeviceSize range = uniform ? limits.maxUniformBufferRange : limits.maxStorageBufferRange;
            bufferInfos[i] = {buf.buffer, 0, std::min<VkDeviceSize>(buf.desc.size, range)};
            writes[i].pBufferInfo = &bufferInfos[i];
            continue;
        }
        const ImageRes* img = findImage(b->image);
        if (!img) return internal(slot() + ": no image " + std::to_string(b->image.id));
        const ImageUsage use = s.kind == BindingKind::SampledImage ? ImageSampled : ImageStorage;
        if (auto why = missingUsage(img->desc, use); !why.empty()) return internal(slot() + ": " + why);
        if (s.kind == BindingKind::SampledImage) {
            CAVITY_ASSIGN(const VkSampler sampler, samplers_.get(*d_, b->sampler));
            imageInfos[i] = {sampler, img->view, VK_IMAGE_LAYOUT_GENERAL};
        } else {
            if (!(img->usage & VK_IMAGE_USAGE_STORAGE_BIT))
                return internal(slot() + ": " + img->describe() + " cannot be a storage image: '" +
                                d_->info.deviceName + "' has no storage-image support for " +
                                formatName(img->desc.format));
            if (img->desc.format != s.format)
                return internal(slot() + ": " + img->describe() + " is bound where the layout declares " +
                                formatName(s.format));
            if (b->mipLevel < 0 || b->mipLevel >= img->levels)
                return internal(slot() + ": " + img->describe() + " has no mip level " + std::to_string(b->mipLevel) +
                                " (it has " + std::to_string(img->levels) + ")");
            imageInfos[i] = {VK_NULL_HANDLE, img->levelViews[size_t(b->mipLevel)], VK_IMAGE_LAYOUT_GENERAL};
        }
        writes[i].pImageInfo = &imageInfos[i];
    }
    CAVITY_ASSIGN(const VkDescriptorSet set, descriptors_.allocate(pipe.setLayout, who));
    for (auto& w : writes) w.dstSet = set;
    vkUpdateDescriptorSets(d_->device, uint32_t(n), writes.data(), 0, nullptr);
    vkCmdBindDescriptorSets(frameCmd_, point, pipe.layout, 0, 1, &set, 0, nullptr);
    return {};
}

void VulkanBackend::dispatch(Pipeline p, std::span<const Bind> binds, int groupsX, int groupsY) {
    if (!recordable("dispatch")) return;
    const auto it = pipelines_.find(p.id);
    if (it == pipelines_.end() || it->second.graphics)
        return fail(internal("dispatch: pipeline " + std::to_string(p.id) + " is not a compute pipeline"));
    const PipelineRes& pipe = it->second;
    const std::string who = "dispatch '" + pipe.label + "'";
    const uint32_t* most = d_->props.limits.maxComputeWorkGroupCount;
    if (groupsX < 0 || groupsY < 0 || uint32_t(groupsX) > most[0] || uint32_t(groupsY) > most[1])
        return fail(internal(who + ": " + std::to_string(groupsX) + "x" + std::to_string(groupsY) +
                             " work groups, the device allows up to " + std::to_string(most[0]) + "x" +
                             std::to_string(most[1])));
    if (Status s = bindResources(pipe, binds, VK_PIPELINE_BIND_POINT_COMPUTE, who); !s) return fail(s.error());
    const SyncScope scope = shaderScope(pipe, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    barriers_.before(*d_, frameCmd_, scope);
    vkCmdBindPipeline(frameCmd_, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.pipeline);
    vkCmdDispatch(frameCmd_, uint32_t(groupsX), uint32_t(groupsY), 1);
    barriers_.recorded(scope.stages, scope.access & kWrites);
}

void VulkanBackend::draw(Pipeline p, std::span<const Bind> binds, const RenderTargets& targets, int vertexCount) {
    if (!recordable("draw")) return;
    const auto it = pipelines_.find(p.id);
    if (it == pipelines_.end() || !it->second.graphics)
        return fail(internal("draw: pipeline " + std::to_string(p.id) + " is not a graphics pipeline"));
    if (Status s = recordDraw(it->second, binds, targets, vertexCount, "draw '" + it->second.label + "'"); !s)
        fail(s.error());
}

Status VulkanBackend::recordDraw(const PipelineRes& pipe, std::span<const Bind> binds, const RenderTargets& t,
                                 int vertexCount, const std::string& who) {
    if (vertexCount < 0) return internal(who + ": " + std::to_string(vertexCount) + " vertices");
    if (t.colors.size() != pipe.colorFormats.size())
        return internal(who + ": " + std::to_string(t.colors.size()) + " color targets for a pipeline with " +
                        std::to_string(pipe.colorFormats.size()));
    int width = 0, height = 0;
    const auto target = [&](Image handle, const std::string& what, ImageUsage use,
                            VkImageUsageFlags usage) -> Result<const ImageRes*> {
        const ImageRes* img = findImage(handle);
        if (!img) return internal(who + ": " + what + " is not an image (" + std::to_string(handle.id) + ")");
        if (auto why = missingUsage(img->desc, use); !why.empty()) return internal(who + ": " + what + " " + why);
        if (!(img->usage & usage))
            return internal(who + ": " + img->describe() + " cannot be a " + what + " on '" +
                            d_->info.deviceName + "'");
        if (width == 0) {
            width = img->width();
            height = img->height();
        }
        if (img->width() != width || img->height() != height)
            return internal(who + ": " + what + " " + img->describe() + " differs in size from the other targets (" +
                            std::to_string(width) + "x" + std::to_string(height) + ")");
        return img;
    };

    std::vector<VkRenderingAttachmentInfo> colors(
        t.colors.size(), vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO));
    for (size_t i = 0; i < colors.size(); ++i) {
        CAVITY_ASSIGN(const ImageRes* img,
                      target(t.colors[i], "color target " + std::to_string(i), ImageColorTarget,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT));
        if (img->desc.format != pipe.colorFormats[i])
            return internal(who + ": color target " + std::to_string(i) + " is " + img->describe() +
                            ", the pipeline writes " + formatName(pipe.colorFormats[i]));
        colors[i].imageView = img->levelViews[0];
        colors[i].imageLayout = VK_IMAGE_LAYOUT_GENERAL;
        colors[i].loadOp = t.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        std::memcpy(colors[i].clearValue.color.float32, t.clearColor, sizeof t.clearColor);
    }
    // A pipeline declares a depth attachment exactly when it tests depth
    // (vk_pipelines.cpp), and the attachments must match what it declares.
    auto depth = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    if (pipe.depth) {
        if (!t.depth) return internal(who + ": the pipeline tests depth but no depth target was given");
        CAVITY_ASSIGN(const ImageRes* img,
                      target(t.depth, "depth target", ImageDepthTarget, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT));
        depth.imageView = img->levelViews[0];
        depth.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
        depth.loadOp = t.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {t.clearDepth, 0};
    } else if (t.depth) {
        return internal(who + ": a depth target was given to a pipeline created without depthTest");
    }
    if (width == 0) return internal(who + ": no render targets");

    CAVITY_TRY(bindResources(pipe, binds, VK_PIPELINE_BIND_POINT_GRAPHICS, who));
    const SyncScope scope = drawScope(pipe, t.clear);
    barriers_.before(*d_, frameCmd_, scope);
    recordRendering(*d_, frameCmd_, pipe, colors, depth, width, height, vertexCount);
    barriers_.recorded(scope.stages, scope.access & kWrites);
    return {};
}

void VulkanBackend::barrier() {
    if (recordable("barrier")) barriers_.barrier();
}

void VulkanBackend::beginScope(const std::string& name) {
    if (!recordable("beginScope")) return;
    if (Status s = timestamps_.beginScope(frameCmd_, name); !s) fail(s.error());
}

void VulkanBackend::endScope() {
    if (!recordable("endScope")) return;
    if (Status s = timestamps_.endScope(frameCmd_); !s) fail(s.error());
}

Status VulkanBackend::submitFrame() {
    if (!cmdOpen_) return {};
    cmdOpen_ = false;
    CAVITY_VK(vkEndCommandBuffer(frameCmd_), "vkEndCommandBuffer (frame)");
    if (error_) return {};   // the recorded commands are incomplete: never run them
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &frameCmd_;
    CAVITY_VK(vkQueueSubmit(d_->queue, 1, &submit, frameFence_), "vkQueueSubmit (frame)");
    CAVITY_VK(vkWaitForFences(d_->device, 1, &frameFence_, VK_TRUE, UINT64_MAX), "vkWaitForFences (frame)");
    CAVITY_VK(vkResetFences(d_->device, 1, &frameFence_), "vkResetFences (frame)");
    return timestamps_.resolve();
}

Status VulkanBackend::endFrame() {
    if (!recording_ && !error_) return internal("endFrame without beginFrame");
    recording_ = false;
    if (cmdOpen_ && !error_)
        if (Status s = timestamps_.checkClosed(); !s) fail(s.error());
    Status s = submitFrame();
    destroyDeferred();
    if (error_) return std::exchange(error_, std::nullopt).value();
    return s;
}

}  // namespace cavity::gpu::vk
