// The OpenGL 4.5 backend's class and its records of images, buffers and
// pipelines, shared by its three files: gl_backend.cpp (context and device
// queries), gl_resources.cpp (images, buffers, pipelines) and gl_commands.cpp
// (frame recording). Private to cavity_backend_gl; createGlBackend is the way in.
#pragma once

#include "backend.h"
#include "gl/egl_context.h"
#include "gl/gl_debug.h"
#include "gl/gl_framebuffers.h"
#include "gl/gl_samplers.h"
#include "gl/gl_timestamps.h"

#include <epoxy/gl.h>

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace cavity::gpu::gl {

struct ImageRecord {
    GLuint texture = 0;
    ImageDesc desc;
    int levels = 1;
};

struct BufferRecord {
    GLuint buffer = 0;
    BufferDesc desc;
};

struct PipelineRecord {
    GLuint program = 0;
    bool graphics = false;
    std::vector<BindingSlot> layout;
    std::vector<Format> colorFormats;   // graphics only
    Format depthFormat = Format::D32;
    bool depthTest = false;
    std::string label;
    PipelineInfo info;
};

inline std::string quoted(const std::string& label) { return label.empty() ? "" : " '" + label + "'"; }

inline std::string describe(const ImageRecord& image) {
    return std::to_string(image.desc.width) + "x" + std::to_string(image.desc.height) + " " +
           formatName(image.desc.format) + quoted(image.desc.label);
}

class GlBackend final : public Backend {
public:
    explicit GlBackend(std::unique_ptr<EglContext> egl) : egl_(std::move(egl)) {}
    ~GlBackend() override;
    Status init(const BackendOptions& options);

    Api api() const override { return Api::OpenGL; }
    const DeviceInfo& info() const override { return info_; }

    Result<Image> createImage(const ImageDesc& desc) override;
    Result<Buffer> createBuffer(const BufferDesc& desc) override;
    void destroy(Image image) override;
    void destroy(Buffer buffer) override;
    void destroy(Pipeline pipeline) override;

    Status uploadImage(Image image, int mipLevel, std::span<const float> pixels) override;
    Result<std::vector<float>> readImage(Image image, int mipLevel) override;
    Status updateBuffer(Buffer buffer, std::span<const std::byte> data, size_t offset) override;

    Result<Pipeline> createComputePipeline(const ComputePipelineDesc& desc) override;
    Result<Pipeline> createGraphicsPipeline(const GraphicsPipelineDesc& desc) override;
    PipelineInfo pipelineInfo(Pipeline pipeline) const override;

    void beginFrame() override;
    void dispatch(Pipeline p, std::span<const Bind> binds, int groupsX, int groupsY) override {
        record(dispatchNow(p, binds, groupsX, groupsY));
    }
    void draw(Pipeline p, std::span<const Bind> binds, const RenderTargets& targets, int vertexCount) override {
        record(drawNow(p, binds, targets, vertexCount));
    }
    void barrier() override { record(barrierNow()); }
    void beginScope(const std::string& name) override { record(startRecording("beginScope"), [&] { return timestamps_.begin(name); }); }
    void endScope() override { record(startRecording("endScope"), [&] { return timestamps_.end(); }); }
    Status endFrame() override;
    std::vector<ScopeTime> scopeTimes() const override { return scopes_; }
    Status finish() override;
    std::vector<std::string> takeDebugMessages() override { return debug_.take(); }

private:
    template <class T, class Map>
    static auto* find(Map& map, T handle) {
        auto it = map.find(handle.id);
        return it == map.end() ? nullptr : &it->second;
    }
    Result<const ImageRecord*> image(Image handle, const std::string& what) const;
    Result<const PipelineRecord*> pipeline(Pipeline handle, bool graphics, const char* op) const;

    // The first error of a frame is the one endFrame reports.
    void record(Status status) {
        if (!status.ok() && sticky_.ok()) sticky_ = std::move(status);
    }
    template <class F>
    void record(Status ready, F&& then) { record(ready.ok() ? then() : ready); }
    Status startRecording(const char* op);
    Status dispatchNow(Pipeline p, std::span<const Bind> binds, int groupsX, int groupsY);
    Status drawNow(Pipeline p, std::span<const Bind> binds, const RenderTargets& targets, int vertexCount);
    Status barrierNow();
    Status finishFrame();
    Status bindResources(const PipelineRecord& pipe, std::span<const Bind> binds, const std::string& what);
    Status owedBarrier(const PipelineRecord& pipe, bool draws);
    uint32_t newId() { return nextId_++; }

    std::unique_ptr<EglContext> egl_;
    DeviceInfo info_;
    std::string spirvUnusable_;
    DebugLog debug_;
    SamplerCache samplers_;
    FramebufferCache framebuffers_;
    Timestamps timestamps_;
    GLuint emptyVertexArray_ = 0;
    std::unordered_map<uint32_t, ImageRecord> images_;
    std::unordered_map<uint32_t, BufferRecord> buffers_;
    std::unordered_map<uint32_t, PipelineRecord> pipelines_;
    uint32_t nextId_ = 1;
    bool inFrame_ = false;
    // barrier() as narrow as what follows it (barrierNow). Only shader image
    // and buffer stores are incoherent in GL; attachment writes and reads are
    // ordered with later commands by the API itself.
    bool storedSinceBarrier_ = false;   // a pass with a storage binding ran since the last barrier()
    bool barrierOwed_ = false;          // the last barrier() followed such a pass
    bool fullBarriers_ = false;         // BackendOptions::fullBarriers
    bool noBarriers_ = false;           // BackendOptions::noBarriers
    GLbitfield barrierIssued_ = 0;      // the glMemoryBarrier bits already issued for it
    Status sticky_;
    std::vector<ScopeTime> scopes_;
};

}  // namespace cavity::gpu::gl
