// backend.h formats as GL sees them: the sized internal format of the
// texture, and the client pixel format and type for upload and readback.
#pragma once

#include "backend.h"

#include <epoxy/gl.h>

#include <cstdint>
#include <span>
#include <vector>

namespace cavity::gpu::gl {

struct GlFormat {
    GLenum internalFormat;   // glTextureStorage2D, glBindImageTexture
    GLenum pixelFormat;      // glTextureSubImage2D, glGetTextureImage
    GLenum uploadType;       // glTextureSubImage2D: what packForUpload produces
};

GlFormat glFormat(Format format);

// Halves and unorm bytes are made here, rounding to nearest even, rather
// than by the driver from GL_FLOAT: drivers round differently (Mesa 22.3
// truncates RGBA16F uploads), and every backend must store the same bits.
// Empty for formats uploaded as GL_FLOAT directly.
std::vector<uint8_t> packForUpload(Format format, std::span<const float> pixels);

}  // namespace cavity::gpu::gl
