#include "vk_formats.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace cavity::gpu::vk {

VkFormat toVkFormat(Format f) {
    switch (f) {
    case Format::R8: return VK_FORMAT_R8_UNORM;
    case Format::R16F: return VK_FORMAT_R16_SFLOAT;
    case Format::R32F: return VK_FORMAT_R32_SFLOAT;
    case Format::RG16F: return VK_FORMAT_R16G16_SFLOAT;
    case Format::RGBA8: return VK_FORMAT_R8G8B8A8_UNORM;
    case Format::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::RGBA32F: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::D32: return VK_FORMAT_D32_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

uint16_t floatToHalf(float f) {
    const uint32_t x = std::bit_cast<uint32_t>(f);
    const uint16_t sign = uint16_t((x >> 16) & 0x8000u);
    const uint32_t a = x & 0x7fffffffu;
    if (a >= 0x7f800000u) return sign | (a > 0x7f800000u ? 0x7e00u : 0x7c00u);  // NaN stays quiet NaN
    // 65520 is halfway between the largest half (65504) and 2^16; ties go to
    // the even neighbour, which is infinity.
    if (a >= 0x477ff000u) return sign | 0x7c00u;
    if (a < 0x38800000u) {
        // Below 2^-14 the result is a half denormal m * 2^-24: shift the
        // 24-bit significand into place and round the dropped bits to even.
        if (a < 0x33000000u) return sign;   // below 2^-25: rounds to zero
        const uint32_t m = (a & 0x7fffffu) | 0x800000u;
        const uint32_t shift = 126u - (a >> 23);   // 14..24
        uint32_t q = m >> shift;
        const uint32_t rem = m & ((1u << shift) - 1), half = 1u << (shift - 1);
        if (rem > half || (rem == half && (q & 1u))) ++q;   // may carry into the smallest normal
        return sign | uint16_t(q);
    }
    // Normal: rebias the exponent (127 -> 15) and round 13 dropped bits to even;
    // a carry out of the mantissa correctly bumps the exponent.
    uint32_t r = a - 0x38000000u;
    r += 0xfffu + ((r >> 13) & 1u);
    return sign | uint16_t(r >> 13);
}

float halfToFloat(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16;
    const uint32_t e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
    if (e == 0) {
        const float v = std::ldexp(float(m), -24);   // zero or denormal, exact
        return sign ? -v : v;
    }
    const uint32_t bits = e == 31 ? (sign | 0x7f800000u | (m << 13))
                                  : (sign | ((e + 112u) << 23) | (m << 13));
    return std::bit_cast<float>(bits);
}

namespace {

uint8_t toUnorm8(float v) {
    if (!(v > 0.0f)) return 0;   // also NaN
    if (v >= 1.0f) return 255;
    return uint8_t(v * 255.0f + 0.5f);
}

}  // namespace

void packTexels(Format f, std::span<const float> in, std::byte* out) {
    switch (f) {
    case Format::R8:
    case Format::RGBA8:
        for (size_t i = 0; i < in.size(); ++i) out[i] = std::byte(toUnorm8(in[i]));
        break;
    case Format::R16F:
    case Format::RG16F:
    case Format::RGBA16F:
        for (size_t i = 0; i < in.size(); ++i) {
            const uint16_t h = floatToHalf(in[i]);
            std::memcpy(out + 2 * i, &h, 2);
        }
        break;
    case Format::D32:
        // Copies into a D32_SFLOAT image must hold values in [0, 1].
        for (size_t i = 0; i < in.size(); ++i) {
            const float d = std::isnan(in[i]) ? 0.0f : std::clamp(in[i], 0.0f, 1.0f);
            std::memcpy(out + 4 * i, &d, 4);
        }
        break;
    case Format::R32F:
    case Format::RGBA32F:
        std::memcpy(out, in.data(), in.size_bytes());
        break;
    }
}

void unpackTexels(Format f, const std::byte* in, std::span<float> out) {
    switch (f) {
    case Format::R8:
    case Format::RGBA8:
        for (size_t i = 0; i < out.size(); ++i) out[i] = float(uint8_t(in[i])) / 255.0f;
        break;
    case Format::R16F:
    case Format::RG16F:
    case Format::RGBA16F:
        for (size_t i = 0; i < out.size(); ++i) {
            uint16_t h;
            std::memcpy(&h, in + 2 * i, 2);
            out[i] = halfToFloat(h);
        }
        break;
    case Format::R32F:
    case Format::RGBA32F:
    case Format::D32:
        std::memcpy(out.data(), in, out.size_bytes());
        break;
    }
}

}  // namespace cavity::gpu::vk
