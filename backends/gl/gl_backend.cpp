// The OpenGL 4.5 implementation of backend.h. GL executes in order on one
// context, so recording a frame is issuing the calls; errors raised meanwhile
// are kept and come back from endFrame, as a command buffer's would.
// This file: the context's state and the device's queries; resources live in
// gl_resources.cpp, frame recording in gl_commands.cpp (the class: gl_backend.h).
#include "gl/gl_backend.h"
#include "gl/gl_errors.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <utility>

namespace cavity::gpu {
namespace gl {
namespace {

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

}  // namespace

Status GlBackend::init(const BackendOptions& options) {
    if (epoxy_gl_version() < 45)
        return unavailable("gl: OpenGL 4.5 needed, " + glString(GL_RENDERER) + " gives " + glString(GL_VERSION));
    fullBarriers_ = options.fullBarriers;
    noBarriers_ = options.noBarriers;
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

Status GlBackend::finish() {
    CAVITY_TRY(egl_->makeCurrent());
    glFinish();
    return checkGl("glFinish");
}

}  // namespace gl

Result<std::unique_ptr<Backend>> createGlBackend(const BackendOptions& options) {
    CAVITY_ASSIGN(auto egl, gl::EglContext::create(options.deviceIndex, options.validation));
    auto backend = std::make_unique<gl::GlBackend>(std::move(egl));
    CAVITY_TRY(backend->init(options));
    return std::unique_ptr<Backend>(std::move(backend));
}

}  // namespace cavity::gpu