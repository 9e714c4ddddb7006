// The OpenGL 4.5 implementation of backend.h. GL executes in order on one
// context, so recording a frame is issuing the calls; errors raised meanwhile
// are kept and come back from endFrame, as a command buffer's would.
#include "backend.h"
#include "gl/egl_context.h"
#include "gl/gl_debug.h"
#include "gl/gl_errors.h"
#include "gl/gl_formats.h"
#include "gl/gl_framebuffers.h"
#include "gl/gl_programs.h"
#include "gl/gl_samplers.h"
#include "gl/gl_timestamps.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <unordered_map>
#include <utility>

namespace cavity::gpu {
namespace gl {
namespace {

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

std::string quoted(const std::string& label) { return label.empty() ? "" : " '" + label + "'"; }

std::string describe(const ImageRecord& image) {
    return std::to_string(image.desc.width) + "x" + std::to_string(image.desc.height) + " " +
           formatName(image.desc.format) + quoted(image.desc.label);
}

const char* kindName(BindingKind kind) {
    switch (kind) {
    case BindingKind::UniformBuffer: return "uniform buffer";
    case BindingKind::StorageBuffer: return "storage buffer";
    case BindingKind::SampledImage: return "sampled image";
    case BindingKind::StorageImage: return "storage image";
    }
    return "?";
}

std::string glString(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

bool isSoftware(std::string renderer) {
    std::transform(renderer.begin(), renderer.end(), renderer.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const char* name : {"llvmpipe", "softpipe", "swrast"})
        if (renderer.find(name) != std::string::npos) return true;
    return false;
}

// Labels show up in KHR_debug messages and in capture tools (RenderDoc, apitrace).
void labelObject(GLenum kind, GLuint object, const std::string& label) {
    if (label.empty()) return;
    GLint maxLength = 256;
    glGetIntegerv(GL_MAX_LABEL_LENGTH, &maxLength);
    glObjectLabel(kind, object, GLsizei(std::min<size_t>(label.size(), size_t(maxLength - 1))), label.data());
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
    GLbitfield barrierIssued_ = 0;      // the glMemoryBarrier bits already issued for it
    Status sticky_;
    std::vector<ScopeTime> scopes_;
};

Status GlBackend::init(const BackendOptions& options) {
    if (epoxy_gl_version() < 45)
        return unavailable("gl: OpenGL 4.5 needed, " + glString(GL_RENDERER) + " gives " + glString(GL_VERSION));
    fullBarriers_ = options.fullBarriers;
    if (options.validation) CAVITY_TRY(debug_.install());
    // backend.h conventions: NDC y = -1 is row 0 (GL's own), depth in [0, 1] as in Vulkan.
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    // Readback rows are floats (4-byte aligned anyway); uploads may be tightly
    // packed bytes, e.g. 13 R8 texels per row.
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Core profile draws need a vertex array object even with no attributes.
    glCreateVertexArrays(1, &emptyVertexArray_);
    CAVITY_TRY(checkGl("initial state (glClipControl, glPixelStorei, glCreateVertexArrays)"));

    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    info_.api = apiName(Api::OpenGL);
    info_.deviceName = glString(GL_RENDERER);
    info_.driver = glString(GL_VERSION) + " (" + egl_->platform() + ")";
    info_.apiVersion = std::to_string(major) + "." + std::to_string(minor);
    info_.vendor = glString(GL_VENDOR);
    info_.softwareRenderer = isSoftware(info_.deviceName);
    if (epoxy_has_gl_extension("GL_EXT_memory_object")) {
        unsigned char uuid[16] = {};
        glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid);
        if (glGetError() == GL_NO_ERROR) info_.uuid = hexUuid(uuid);
    }
    if (epoxy_has_gl_extension("GL_NV_shader_thread_group")) {
        GLint sms = 0;
        glGetIntegerv(GL_SM_COUNT_NV, &sms);
        if (glGetError() == GL_NO_ERROR && sms > 0) info_.smCount = sms;
    }

    // Lets tests and bug reports exercise the GLSL path on a driver with SPIR-V.
    const char* force = std::getenv("CAVITY_GL_FORCE_GLSL");
    if (force && std::string(force) == "1") spirvUnusable_ = "CAVITY_GL_FORCE_GLSL=1";
    else if (epoxy_gl_version() < 46 && !epoxy_has_gl_extension("GL_ARB_gl_spirv"))
        spirvUnusable_ = "driver lacks GL_ARB_gl_spirv";
    return checkGl("device queries");
}

GlBackend::~GlBackend() {
    // Objects of a context die with it; deleting them first keeps capture
    // tools and leak checkers quiet. Never touch another backend's context.
    if (!egl_->makeCurrent().ok()) return;
    samplers_.release();
    framebuffers_.release();
    timestamps_.release();
    for (auto& [id, image] : images_) glDeleteTextures(1, &image.texture);
    for (auto& [id, buffer] : buffers_) glDeleteBuffers(1, &buffer.buffer);
    for (auto& [id, pipe] : pipelines_) glDeleteProgram(pipe.program);
    glDeleteVertexArrays(1, &emptyVertexArray_);
    debug_.uninstall();
}

Result<const ImageRecord*> GlBackend::image(Image handle, const std::string& what) const {
    auto it = images_.find(handle.id);
    if (it == images_.end()) return internal("gl: " + what + ": image #" + std::to_string(handle.id) + " does not exist");
    return &it->second;
}

Result<const PipelineRecord*> GlBackend::pipeline(Pipeline handle, bool graphics, const char* op) const {
    auto it = pipelines_.find(handle.id);
    if (it == pipelines_.end() || it->second.graphics != graphics)
        return internal(std::string("gl: ") + op + ": pipeline #" + std::to_string(handle.id) + " is no " +
                        (graphics ? "graphics" : "compute") + " pipeline");
    return &it->second;
}

// ---- Resources ----

Result<Image> GlBackend::createImage(const ImageDesc& desc) {
    CAVITY_TRY(egl_->makeCurrent());
    ImageRecord record{0, desc, std::max(desc.mipLevels, 1)};
    glCreateTextures(GL_TEXTURE_2D, 1, &record.texture);
    glTextureStorage2D(record.texture, record.levels, glFormat(desc.format).internalFormat, desc.width, desc.height);
    labelObject(GL_TEXTURE, record.texture, desc.label);
    const Status status = checkGl("glTextureStorage2D " + describe(record) +
                                  (record.levels > 1 ? ", " + std::to_string(record.levels) + " levels" : ""));
    if (!status.ok()) {
        glDeleteTextures(1, &record.texture);
        return status.error();
    }
    const uint32_t id = newId();
    images_.emplace(id, std::move(record));
    return Image{id};
}

Result<Buffer> GlBackend::createBuffer(const BufferDesc& desc) {
    CAVITY_TRY(egl_->makeCurrent());
    BufferRecord record{0, desc};
    glCreateBuffers(1, &record.buffer);
    glNamedBufferStorage(record.buffer, GLsizeiptr(desc.size), nullptr, GL_DYNAMIC_STORAGE_BIT);
    labelObject(GL_BUFFER, record.buffer, desc.label);
    const Status status = checkGl("glNamedBufferStorage " + std::to_string(desc.size) + " bytes" + quoted(desc.label));
    if (!status.ok()) {
        glDeleteBuffers(1, &record.buffer);
        return status.error();
    }
    const uint32_t id = newId();
    buffers_.emplace(id, std::move(record));
    return Buffer{id};
}

void GlBackend::destroy(Image handle) {
    auto it = images_.find(handle.id);
    if (it == images_.end() || !egl_->makeCurrent().ok()) return;
    framebuffers_.forget(handle.id);
    glDeleteTextures(1, &it->second.texture);
    images_.erase(it);
}

void GlBackend::destroy(Buffer handle) {
    auto it = buffers_.find(handle.id);
    if (it == buffers_.end() || !egl_->makeCurrent().ok()) return;
    glDeleteBuffers(1, &it->second.buffer);
    buffers_.erase(it);
}

void GlBackend::destroy(Pipeline handle) {
    auto it = pipelines_.find(handle.id);
    if (it == pipelines_.end() || !egl_->makeCurrent().ok()) return;
    glDeleteProgram(it->second.program);
    pipelines_.erase(it);
}

Status GlBackend::uploadImage(Image handle, int level, std::span<const float> pixels) {
    CAVITY_TRY(egl_->makeCurrent());
    CAVITY_ASSIGN(const ImageRecord* img, image(handle, "uploadImage"));
    const std::string what = "uploadImage " + describe(*img) + " level " + std::to_string(level);
    if (auto why = missingUsage(img->desc, ImageTransfer); !why.empty()) return internal("gl: " + what + ": " + why);
    if (level < 0 || level >= img->levels)
        return internal("gl: " + what + ": the image has " + std::to_string(img->levels) + " levels");
    const int w = std::max(img->desc.width >> level, 1), h = std::max(img->desc.height >> level, 1);
    const size_t expected = size_t(w) * size_t(h) * size_t(channelCount(img->desc.format));
    if (pixels.size() != expected)
        return internal("gl: " + what + ": " + std::to_string(pixels.size()) + " floats given, " + std::to_string(w) +
                        "x" + std::to_string(h) + "x" + std::to_string(channelCount(img->desc.format)) + " expected");
    const GlFormat format = glFormat(img->desc.format);
    const std::vector<uint8_t> packed = packForUpload(img->desc.format, pixels);
    // Image stores of earlier passes must land before the texels are replaced.
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glTextureSubImage2D(img->texture, level, 0, 0, w, h, format.pixelFormat, format.uploadType,
                        packed.empty() ? static_cast<const void*>(pixels.data()) : packed.data());
    return checkGl("glTextureSubImage2D, " + what);
}

Result<std::vector<float>> GlBackend::readImage(Image handle, int level) {
    CAVITY_TRY(egl_->makeCurrent());
    CAVITY_ASSIGN(const ImageRecord* img, image(handle, "readImage"));
    const std::string what = "readImage " + describe(*img) + " level " + std::to_string(level);
    if (auto why = missingUsage(img->desc, ImageTransfer); !why.empty()) return internal("gl: " + what + ": " + why);
    if (level < 0 || level >= img->levels)
        return internal("gl: " + what + ": the image has " + std::to_string(img->levels) + " levels");
    const int w = std::max(img->desc.width >> level, 1), h = std::max(img->desc.height >> level, 1);
    std::vector<float> pixels(size_t(w) * size_t(h) * size_t(channelCount(img->desc.format)));
    // Image stores are incoherent with texture reads until this barrier.
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(img->texture, level, glFormat(img->desc.format).pixelFormat, GL_FLOAT,
                      GLsizei(pixels.size() * sizeof(float)), pixels.data());
    CAVITY_TRY(checkGl("glGetTextureImage, " + what));
    return pixels;
}

Status GlBackend::updateBuffer(Buffer handle, std::span<const std::byte> data, size_t offset) {
    CAVITY_TRY(egl_->makeCurrent());
    const BufferRecord* buf = find(buffers_, handle);
    if (!buf) return internal("gl: updateBuffer: buffer #" + std::to_string(handle.id) + " does not exist");
    const std::string what = "updateBuffer" + quoted(buf->desc.label) + " " + std::to_string(data.size()) +
                             " bytes at " + std::to_string(offset);
    if (offset > buf->desc.size || data.size() > buf->desc.size - offset)
        return internal("gl: " + what + ": the buffer has " + std::to_string(buf->desc.size) + " bytes");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glNamedBufferSubData(buf->buffer, GLintptr(offset), GLsizeiptr(data.size()), data.data());
    return checkGl("glNamedBufferSubData, " + what);
}

// ---- Pipelines ----

Result<Pipeline> GlBackend::createComputePipeline(const ComputePipelineDesc& desc) {
    CAVITY_TRY(egl_->makeCurrent());
    const ShaderSource* stages[] = {&desc.shader};
    BuiltProgram built;
    {
        DebugLog::Mute mute(debug_);
        CAVITY_ASSIGN(built, buildProgram(stages, spirvUnusable_));
    }
    PipelineRecord record{built.program, false, desc.layout, {}, Format::D32, false,
                          desc.label.empty() ? desc.shader.name : desc.label, built.info};
    // The dispatch grid is computed from the descriptor's size; a mismatch
    // would silently leave pixels unwritten.
    GLint size[3] = {0, 0, 0};
    glGetProgramiv(record.program, GL_COMPUTE_WORK_GROUP_SIZE, size);
    labelObject(GL_PROGRAM, record.program, record.label);
    Status status = checkGl("compute pipeline '" + record.label + "'");
    if (status.ok() && (size[0] != desc.localSizeX || size[1] != desc.localSizeY || size[2] != 1))
        status = internal("gl: compute pipeline '" + record.label + "': shader local size " + std::to_string(size[0]) +
                          "x" + std::to_string(size[1]) + "x" + std::to_string(size[2]) + ", description says " +
                          std::to_string(desc.localSizeX) + "x" + std::to_string(desc.localSizeY));
    if (!status.ok()) {
        glDeleteProgram(record.program);
        return status.error();
    }
    const uint32_t id = newId();
    pipelines_.emplace(id, std::move(record));
    return Pipeline{id};
}

Result<Pipeline> GlBackend::createGraphicsPipeline(const GraphicsPipelineDesc& desc) {
    CAVITY_TRY(egl_->makeCurrent());
    const ShaderSource* stages[] = {&desc.vertex, &desc.fragment};
    BuiltProgram built;
    {
        DebugLog::Mute mute(debug_);
        CAVITY_ASSIGN(built, buildProgram(stages, spirvUnusable_));
    }
    PipelineRecord record{built.program,    true,           desc.layout,
                          desc.colorFormats, desc.depthFormat, desc.depthTest,
                          desc.label.empty() ? desc.fragment.name : desc.label, built.info};
    labelObject(GL_PROGRAM, record.program, record.label);
    const Status status = checkGl("graphics pipeline '" + record.label + "'");
    if (!status.ok()) {
        glDeleteProgram(record.program);
        return status.error();
    }
    const uint32_t id = newId();
    pipelines_.emplace(id, std::move(record));
    return Pipeline{id};
}

PipelineInfo GlBackend::pipelineInfo(Pipeline handle) const {
    auto it = pipelines_.find(handle.id);
    return it == pipelines_.end() ? PipelineInfo{} : it->second.info;
}

// ---- Recording ----

void GlBackend::beginFrame() {
    if (inFrame_) record(internal("gl: beginFrame: the previous frame was not ended"));
    inFrame_ = true;
    timestamps_.reset();
}

Status GlBackend::startRecording(const char* op) {
    if (!inFrame_) return internal(std::string("gl: ") + op + " outside beginFrame/endFrame");
    return egl_->makeCurrent();
}

// Binding numbers are shared across kinds (backend.h), so each maps directly
// to its UBO / SSBO index, texture unit or image unit.
Status GlBackend::bindResources(const PipelineRecord& pipe, std::span<const Bind> binds, const std::string& what) {
    for (const Bind& bind : binds)
        if (std::none_of(pipe.layout.begin(), pipe.layout.end(), [&](const BindingSlot& s) { return s.binding == bind.binding; }))
            return internal("gl: " + what + ": binding " + std::to_string(bind.binding) + " is not in the pipeline layout");
    for (const BindingSlot& slot : pipe.layout) {
        const std::string at = what + ": binding " + std::to_string(slot.binding) + " (" + kindName(slot.kind) + ")";
        auto bind = std::find_if(binds.begin(), binds.end(), [&](const Bind& b) { return b.binding == slot.binding; });
        if (bind == binds.end()) return internal("gl: " + at + " has no Bind");
        switch (slot.kind) {
        case BindingKind::UniformBuffer:
        case BindingKind::StorageBuffer: {
            const BufferRecord* buf = find(buffers_, bind->buffer);
            if (!buf) return internal("gl: " + at + ": buffer #" + std::to_string(bind->buffer.id) + " does not exist");
            glBindBufferBase(slot.kind == BindingKind::UniformBuffer ? GL_UNIFORM_BUFFER : GL_SHADER_STORAGE_BUFFER,
                             slot.binding, buf->buffer);
            break;
        }
        case BindingKind::SampledImage: {
            CAVITY_ASSIGN(const ImageRecord* img, image(bind->image, at));
            if (auto why = missingUsage(img->desc, ImageSampled); !why.empty()) return internal("gl: " + at + ": " + why);
            CAVITY_ASSIGN(const GLuint sampler, samplers_.get(bind->sampler));
            glBindTextureUnit(slot.binding, img->texture);
            glBindSampler(slot.binding, sampler);
            break;
        }
        case BindingKind::StorageImage: {
            CAVITY_ASSIGN(const ImageRecord* img, image(bind->image, at));
            if (auto why = missingUsage(img->desc, ImageStorage); !why.empty()) return internal("gl: " + at + ": " + why);
            if (img->desc.format != slot.format)
                return internal("gl: " + at + ": the layout says " + formatName(slot.format) + ", image is " + describe(*img));
            if (bind->mipLevel < 0 || bind->mipLevel >= img->levels)
                return internal("gl: " + at + ": " + describe(*img) + " has no mip level " +
                                std::to_string(bind->mipLevel) + " (it has " + std::to_string(img->levels) + ")");
            glBindImageTexture(slot.binding, img->texture, bind->mipLevel, GL_FALSE, 0, GL_READ_WRITE,
                               glFormat(slot.format).internalFormat);
            break;
        }
        }
    }
    return checkGl(what + ": binding resources");
}

Status GlBackend::dispatchNow(Pipeline p, std::span<const Bind> binds, int groupsX, int groupsY) {
    CAVITY_TRY(startRecording("dispatch"));
    CAVITY_ASSIGN(const PipelineRecord* pipe, pipeline(p, false, "dispatch"));
    const std::string what = "dispatch '" + pipe->label + "' " + std::to_string(groupsX) + "x" + std::to_string(groupsY);
    if (groupsX < 0 || groupsY < 0) return internal("gl: " + what + ": negative group count");
    CAVITY_TRY(bindResources(*pipe, binds, what));
    CAVITY_TRY(owedBarrier(*pipe, false));
    glUseProgram(pipe->program);
    glDispatchCompute(GLuint(groupsX), GLuint(groupsY), 1);
    return checkGl("glDispatchCompute, " + what);
}

Status GlBackend::drawNow(Pipeline p, std::span<const Bind> binds, const RenderTargets& targets, int vertexCount) {
    CAVITY_TRY(startRecording("draw"));
    CAVITY_ASSIGN(const PipelineRecord* pipe, pipeline(p, true, "draw"));
    const std::string what = "draw '" + pipe->label + "'";
    if (targets.colors.size() != pipe->colorFormats.size())
        return internal("gl: " + what + ": " + std::to_string(targets.colors.size()) + " color targets, the pipeline has " +
                        std::to_string(pipe->colorFormats.size()));
    if (pipe->depthTest && !targets.depth) return internal("gl: " + what + ": depth test without a depth target");

    // Every target must match the pipeline's format and share one size (the viewport).
    int width = -1, height = -1;
    auto attach = [&](Image handle, Format expected, ImageUsage use,
                      const std::string& role) -> Result<FramebufferCache::Attachment> {
        CAVITY_ASSIGN(const ImageRecord* img, image(handle, what + " " + role));
        if (auto why = missingUsage(img->desc, use); !why.empty())
            return internal("gl: " + what + ": " + role + " " + why);
        if (img->desc.format != expected)
            return internal("gl: " + what + ": " + role + " is " + describe(*img) + ", the pipeline says " + formatName(expected));
        if (width >= 0 && (img->desc.width != width || img->desc.height != height))
            return internal("gl: " + what + ": " + role + " is " + describe(*img) + ", other targets are " +
                            std::to_string(width) + "x" + std::to_string(height));
        width = img->desc.width;
        height = img->desc.height;
        return FramebufferCache::Attachment{handle.id, img->texture};
    };
    std::vector<FramebufferCache::Attachment> colors;
    for (size_t i = 0; i < targets.colors.size(); ++i) {
        CAVITY_ASSIGN(auto color, attach(targets.colors[i], pipe->colorFormats[i], ImageColorTarget,
                                           "color target " + std::to_string(i)));
        colors.push_back(color);
    }
    FramebufferCache::Attachment depth;
    if (targets.depth) {
        CAVITY_ASSIGN(depth, attach(targets.depth, pipe->depthFormat, ImageDepthTarget, "depth target"));
    }
    if (width < 0) return internal("gl: " + what + ": no render targets");
    CAVITY_ASSIGN(const GLuint framebuffer, framebuffers_.get(colors, depth, what));

    // Before the clear: it writes the targets too.
    CAVITY_TRY(owedBarrier(*pipe, true));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    if (targets.clear) {
        glDepthMask(GL_TRUE);   // clears honour the depth write mask
        for (size_t i = 0; i < colors.size(); ++i) glClearNamedFramebufferfv(framebuffer, GL_COLOR, GLint(i), targets.clearColor);
        if (depth.image) glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &targets.clearDepth);
    }
    if (pipe->depthTest) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    CAVITY_TRY(bindResources(*pipe, binds, what));
    glUseProgram(pipe->program);
    glBindVertexArray(emptyVertexArray_);
    glDrawArrays(GL_TRIANGLES, 0, vertexCount);
    return checkGl("glDrawArrays, " + what + " " + std::to_string(vertexCount) + " vertices into " +
                   std::to_string(width) + "x" + std::to_string(height));
}

Status GlBackend::barrierNow() {
    CAVITY_TRY(startRecording("barrier"));
    if (fullBarriers_) {
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        return checkGl("glMemoryBarrier(GL_ALL_BARRIER_BITS)");
    }
    if (!storedSinceBarrier_) return {};   // two barrier() calls in a row are one
    storedSinceBarrier_ = false;
    barrierOwed_ = true;
    barrierIssued_ = 0;
    return {};
}

// The glMemoryBarrier bits name how later commands read what earlier image
// and buffer stores wrote, so they wait for the pass that reads: sampling
// needs TEXTURE_FETCH, imageLoad/imageStore SHADER_IMAGE_ACCESS, storage
// buffers SHADER_STORAGE, render targets FRAMEBUFFER. Every pass until the
// next barrier() gets the bits it needs, once. A storage binding counts as a
// store: the layout does not say whether the shader writes it.
Status GlBackend::owedBarrier(const PipelineRecord& pipe, bool draws) {
    if (fullBarriers_) return {};   // barrierNow() issued every bit already
    GLbitfield need = draws ? GL_FRAMEBUFFER_BARRIER_BIT : 0;
    bool stores = false;
    for (const BindingSlot& slot : pipe.layout) {
        switch (slot.kind) {
        case BindingKind::UniformBuffer: break;   // written by updateBuffer only, which has its own barrier
        case BindingKind::SampledImage: need |= GL_TEXTURE_FETCH_BARRIER_BIT; break;
        case BindingKind::StorageImage: need |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT; stores = true; break;
        case BindingKind::StorageBuffer: need |= GL_SHADER_STORAGE_BARRIER_BIT; stores = true; break;
        }
    }
    storedSinceBarrier_ |= stores;
    need &= ~barrierIssued_;
    if (!barrierOwed_ || !need) return {};
    barrierIssued_ |= need;
    glMemoryBarrier(need);
    return checkGl("glMemoryBarrier before '" + pipe.label + "'");
}

Status GlBackend::finishFrame() {
    if (!inFrame_) return internal("gl: endFrame without beginFrame");
    inFrame_ = false;
    CAVITY_TRY(egl_->makeCurrent());
    if (const std::string* open = timestamps_.open()) return internal("gl: endFrame: scope '" + *open + "' was not ended");
    glFinish();
    CAVITY_TRY(checkGl("glFinish at endFrame"));
    CAVITY_ASSIGN(scopes_, timestamps_.resolve());
    return {};
}

Status GlBackend::endFrame() {
    scopes_.clear();
    const Status finished = finishFrame();
    Status status = std::exchange(sticky_, Status{});
    if (status.ok()) status = finished;
    if (!status.ok()) scopes_.clear();
    return status;
}

Status GlBackend::finish() {
    CAVITY_TRY(egl_->makeCurrent());
    glFinish();
    return checkGl("glFinish");
}

}  // namespace
}  // namespace gl

Result<std::unique_ptr<Backend>> createGlBackend(const BackendOptions& options) {
    CAVITY_ASSIGN(auto egl, gl::EglContext::create(options.deviceIndex, options.validation));
    auto backend = std::make_unique<gl::GlBackend>(std::move(egl));
    CAVITY_TRY(backend->init(options));
    return std::unique_ptr<Backend>(std::move(backend));
}

}  // namespace cavity::gpu
