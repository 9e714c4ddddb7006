// The Vulkan implementation of gpu::Backend (backend.h). Resources live in
// vk_resources.cpp and vk_pipelines.cpp; frame recording in vk_commands.cpp;
// this class owns them by handle id. Not thread-safe, like the interface.
#pragma once

#include "backend.h"
#include "timestamps.h"
#include "vk_barriers.h"
#include "vk_descriptors.h"
#include "vk_device.h"
#include "vk_pipelines.h"
#include "vk_resources.h"

#include <memory>
#include <optional>
#include <unordered_map>

namespace cavity::gpu::vk {

class VulkanBackend final : public Backend {
public:
    explicit VulkanBackend(std::unique_ptr<Device> device);
    ~VulkanBackend() override;
    Status init();   // the frame's command buffer and fence

    Api api() const override { return Api::Vulkan; }
    const DeviceInfo& info() const override { return d_->info; }

    Result<Image> createImage(const ImageDesc&) override;
    Result<Buffer> createBuffer(const BufferDesc&) override;
    void destroy(Image) override;
    void destroy(Buffer) override;
    void destroy(Pipeline) override;

    Status uploadImage(Image, int mipLevel, std::span<const float> pixels) override;
    Result<std::vector<float>> readImage(Image, int mipLevel) override;
    Status updateBuffer(Buffer, std::span<const std::byte> data, size_t offset) override;

    Result<Pipeline> createComputePipeline(const ComputePipelineDesc&) override;
    Result<Pipeline> createGraphicsPipeline(const GraphicsPipelineDesc&) override;
    PipelineInfo pipelineInfo(Pipeline) const override;

    void beginFrame() override;
    void dispatch(Pipeline, std::span<const Bind>, int groupsX, int groupsY) override;
    void draw(Pipeline, std::span<const Bind>, const RenderTargets&, int vertexCount) override;
    void barrier() override;
    void beginScope(const std::string& name) override;
    void endScope() override;
    Status endFrame() override;
    std::vector<ScopeTime> scopeTimes() const override { return timestamps_.times(); }
    Status finish() override;

    std::vector<std::string> takeDebugMessages() override { return d_->takeMessages(); }

private:
    // Recording: the first error of a frame is kept and the rest of the
    // frame's commands are dropped, as a command buffer would.
    bool recordable(const char* op);
    void fail(Error e);
    Status recordDraw(const PipelineRes& pipe, std::span<const Bind> binds, const RenderTargets& t,
                      int vertexCount, const std::string& who);
    Status bindResources(const PipelineRes& pipe, std::span<const Bind> binds, VkPipelineBindPoint point,
                         const std::string& who);
    Status submitFrame();
    void destroyDeferred();

    const ImageRes* findImage(Image i) const;

    std::unique_ptr<Device> d_;   // first: destroyed last
    DescriptorPools descriptors_;
    Timestamps timestamps_;
    SamplerCache samplers_;
    BarrierTracker barriers_;
    VkCommandPool framePool_ = VK_NULL_HANDLE;
    VkCommandBuffer frameCmd_ = VK_NULL_HANDLE;
    VkFence frameFence_ = VK_NULL_HANDLE;

    std::unordered_map<uint32_t, ImageRes> images_;
    std::unordered_map<uint32_t, BufferRes> buffers_;
    std::unordered_map<uint32_t, PipelineRes> pipelines_;
    uint32_t nextId_ = 1;

    bool recording_ = false;   // between beginFrame and endFrame
    bool cmdOpen_ = false;     // frameCmd_ is in the recording state
    std::optional<Error> error_;
    // Destroyed during recording: kept until the frame has completed.
    std::vector<Image> deadImages_;
    std::vector<Buffer> deadBuffers_;
    std::vector<Pipeline> deadPipelines_;
};

}  // namespace cavity::gpu::vk
