// Framebuffer objects, one per combination of render targets, made once and
// reused by every draw into the same images (a pass chain has a handful).
#pragma once

#include "result.h"

#include <epoxy/gl.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace cavity::gpu::gl {

class FramebufferCache {
public:
    struct Attachment {
        uint32_t image = 0;   // backend handle id: the cache key
        GLuint texture = 0;
    };

    // A complete framebuffer drawing colors[i] to location i, with an optional
    // depth attachment (image 0: none). `what` names the draw in errors.
    Result<GLuint> get(std::span<const Attachment> colors, Attachment depth, const std::string& what);
    // Drops every framebuffer that uses the image, before it is deleted.
    void forget(uint32_t image);
    void release();   // needs the context current; otherwise the framebuffers die with it

private:
    struct Entry {
        std::vector<uint32_t> key;   // depth image, then color images
        GLuint framebuffer = 0;
    };
    std::vector<Entry> entries_;
};

}  // namespace cavity::gpu::gl
