// The GL backend's frame recording: each dispatch, draw and barrier is
// issued as it is recorded, its first error kept for endFrame (gl_backend.h).
#include "gl/gl_backend.h"
#include "gl/gl_errors.h"
#include "gl/gl_formats.h"

#include <algorithm>
#include <utility>

namespace cavity::gpu::gl {

namespace {

const char* kindName(BindingKind kind) {
    switch (kind) {
    case BindingKind::UniformBuffer: return "uniform buffer";
    case BindingKind::StorageBuffer: return "storage buffer";
    case BindingKind::SampledImage: return "sampled image";
    case BindingKind::StorageImage: return "storage image";
    }
    return "?";
}

}  // namespace

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
    if (noBarriers_) return {};
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

}  // namespace cavity::gpu::gl
