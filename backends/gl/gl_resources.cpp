// The GL backend's images, buffers and pipelines: created, filled, read back
// and destroyed outside frames, with the context made current for each call.
#include "gl/gl_backend.h"
#include "gl/gl_errors.h"
#include "gl/gl_formats.h"
#include "gl/gl_programs.h"

#include <algorithm>
#include <utility>

namespace cavity::gpu::gl {

namespace {

// Labels show up in KHR_debug messages and in capture tools (RenderDoc, apitrace).
void labelObject(GLenum kind, GLuint object, const std::string& label) {
    if (label.empty()) return;
    GLint maxLength = 256;
    glGetIntegerv(GL_MAX_LABEL_LENGTH, &maxLength);
    glObjectLabel(kind, object, GLsizei(std::min<size_t>(label.size(), size_t(maxLength - 1))), label.data());
}

}  // namespace

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
    PipelineInfo info = it == pipelines_.end() ? PipelineInfo{} : it->second.info;
    info.statsReason = "OpenGL has no query for a program's compiled statistics";
    return info;
}

}  // namespace cavity::gpu::gl
