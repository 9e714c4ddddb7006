#include "gl/gl_formats.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cavity::gpu::gl {
namespace {

// IEEE binary16, round to nearest even; overflow to infinity, NaN stays NaN.
uint16_t toHalf(float value) {
    uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    const auto sign = uint16_t((bits >> 16) & 0x8000u);
    const uint32_t magnitude = bits & 0x7fffffffu;
    if (magnitude >= 0x7f800000u) return sign | (magnitude > 0x7f800000u ? 0x7e00u : 0x7c00u);
    if (magnitude >= 0x477ff000u) return sign | 0x7c00u;   // rounds to 65536 or beyond
    if (magnitude < 0x38800000u) {
        // Below 2^-14: a subnormal half counts units of 2^-24. The scaling is
        // exact, and nearbyint rounds to even in the default rounding mode.
        float m = 0;
        std::memcpy(&m, &magnitude, sizeof m);
        return sign | uint16_t(std::nearbyint(m * 16777216.0f));
    }
    // Rebias the exponent (127 -> 15) and round 23 mantissa bits to 10; a
    // carry out of the mantissa correctly bumps the exponent.
    const uint32_t rebiased = magnitude - 0x38000000u;
    return sign | uint16_t((rebiased + 0x0fffu + ((rebiased >> 13) & 1u)) >> 13);
}

uint8_t toUnorm8(float value) {
    const float clamped = value > 0 ? std::min(value, 1.0f) : 0.0f;   // NaN -> 0, as GL does
    // Round half up, as GPUs convert float to unorm (and as the Vulkan backend does).
    return uint8_t(std::floor(clamped * 255.0f + 0.5f));
}

}  // namespace

GlFormat glFormat(Format format) {
    switch (format) {
    case Format::R8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    case Format::R16F: return {GL_R16F, GL_RED, GL_HALF_FLOAT};
    case Format::R32F: return {GL_R32F, GL_RED, GL_FLOAT};
    case Format::RG16F: return {GL_RG16F, GL_RG, GL_HALF_FLOAT};
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
            const uint16_t half = toHalf(pixels[i]);
            std::memcpy(&packed[i * sizeof half], &half, sizeof half);
        }
        break;
    case GL_UNSIGNED_BYTE:
        packed.resize(pixels.size());
        std::transform(pixels.begin(), pixels.end(), packed.begin(), toUnorm8);
        break;
    }
    return packed;
}

}  // namespace cavity::gpu::gl
