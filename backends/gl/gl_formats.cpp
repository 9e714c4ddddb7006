#include "gl/gl_formats.h"

#include "texels/texels.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cavity::gpu::gl {
GlFormat glFormat(Format format) {
    switch (format) {
    case Format::R8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    case Format::R16F: return {GL_R16F, GL_RED, GL_HALF_FLOAT};
    case Format::R32F: return {GL_R32F, GL_RED, GL_FLOAT};
    case Format::RG16F: return {GL_RG16F, GL_RG, GL_HALF_FLOAT};
    case Format::RG32F: return {GL_RG32F, GL_RG, GL_FLOAT};
    case Format::RGBA8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::RGBA16F: return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT};
    case Format::RGBA32F: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case Format::D32: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    }
    return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
}

std::vector<uint8_t> packForUpload(Format format, std::span<const float> pixels) {
    std::vector<uint8_t> packed;
    switch (glFormat(format).uploadType) {
    case GL_HALF_FLOAT:
        packed.resize(pixels.size() * sizeof(uint16_t));
        for (size_t i = 0; i < pixels.size(); ++i) {
            const uint16_t half = texels::toHalf(pixels[i]);
            std::memcpy(&packed[i * sizeof half], &half, sizeof half);
        }
        break;
    case GL_UNSIGNED_BYTE:
        packed.resize(pixels.size());
        std::transform(pixels.begin(), pixels.end(), packed.begin(), texels::toUnorm8);
        break;
    }
    return packed;
}

}  // namespace cavity::gpu::gl
