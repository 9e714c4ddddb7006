#include "vk_formats.h"

#include "texels/texels.h"

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
    case Format::RG32F: return VK_FORMAT_R32G32_SFLOAT;
    case Format::RGBA8: return VK_FORMAT_R8G8B8A8_UNORM;
    case Format::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::RGBA32F: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::D32: return VK_FORMAT_D32_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

void packTexels(Format f, std::span<const float> in, std::byte* out) {
    switch (f) {
    case Format::R8:
    case Format::RGBA8:
        for (size_t i = 0; i < in.size(); ++i) out[i] = std::byte(texels::toUnorm8(in[i]));
        break;
    case Format::R16F:
    case Format::RG16F:
    case Format::RGBA16F:
        for (size_t i = 0; i < in.size(); ++i) {
            const uint16_t h = texels::toHalf(in[i]);
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
    case Format::RG32F:
    case Format::RGBA32F:
        std::memcpy(out, in.data(), in.size_bytes());
        break;
    }
}

void unpackTexels(Format f, const std::byte* in, std::span<float> out) {
    switch (f) {
    case Format::R8:
    case Format::RGBA8:
        for (size_t i = 0; i < out.size(); ++i) out[i] = texels::fromUnorm8(uint8_t(in[i]));
        break;
    case Format::R16F:
    case Format::RG16F:
    case Format::RGBA16F:
        for (size_t i = 0; i < out.size(); ++i) {
            uint16_t h;
            std::memcpy(&h, in + 2 * i, 2);
            out[i] = texels::fromHalf(h);
        }
        break;
    case Format::R32F:
    case Format::RG32F:
    case Format::RGBA32F:
    case Format::D32:
        std::memcpy(out.data(), in, out.size_bytes());
        break;
    }
}

}  // namespace cavity::gpu::vk
