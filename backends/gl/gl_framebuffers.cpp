#include "gl/gl_framebuffers.h"

#include "gl/gl_errors.h"

#include <algorithm>

namespace cavity::gpu::gl {
namespace {

const char* statusName(GLenum status) {
    switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    }
    return "unknown framebuffer status";
}

}  // namespace

void FramebufferCache::release() {
    for (const Entry& e : entries_) glDeleteFramebuffers(1, &e.framebuffer);
    entries_.clear();
}

Result<GLuint> FramebufferCache::get(std::span<const Attachment> colors, Attachment depth, const std::string& what) {
    std::vector<uint32_t> key{depth.image};
    for (const Attachment& c : colors) key.push_back(c.image);
    for (const Entry& e : entries_)
        if (e.key == key) return e.framebuffer;

    GLuint framebuffer = 0;
    glCreateFramebuffers(1, &framebuffer);
    std::vector<GLenum> drawBuffers;
    for (size_t i = 0; i < colors.size(); ++i) {
        drawBuffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
        glNamedFramebufferTexture(framebuffer, drawBuffers.back(), colors[i].texture, 0);
    }
    if (depth.image) glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth.texture, 0);
    if (drawBuffers.empty()) glNamedFramebufferDrawBuffer(framebuffer, GL_NONE);
    else glNamedFramebufferDrawBuffers(framebuffer, GLsizei(drawBuffers.size()), drawBuffers.data());
    Status status = checkGl("framebuffer for " + what);
    if (status.ok()) {
        const GLenum complete = glCheckNamedFramebufferStatus(framebuffer, GL_DRAW_FRAMEBUFFER);
        if (complete != GL_FRAMEBUFFER_COMPLETE) status = internal("gl: framebuffer for " + what + ": " + statusName(complete));
    }
    if (!status.ok()) {
        glDeleteFramebuffers(1, &framebuffer);
        return status.error();
    }
    entries_.push_back({std::move(key), framebuffer});
    return framebuffer;
}

void FramebufferCache::forget(uint32_t image) {
    if (image == 0) return;   // 0 stands for "no depth" in the keys
    std::erase_if(entries_, [&](const Entry& e) {
        if (std::find(e.key.begin(), e.key.end(), image) == e.key.end()) return false;
        glDeleteFramebuffers(1, &e.framebuffer);
        return true;
    });
}

}  // namespace cavity::gpu::gl
