#include "core/digest.h"

#include <bit>
#include <cstdio>

namespace cavity::core {

// The digest is of the little-endian bytes; hashing memory as it lies is
// only that on a little-endian machine (every machine Cavity runs on).
static_assert(std::endian::native == std::endian::little, "image digests assume a little-endian host");

uint64_t fnv1a64(const void* data, size_t size, uint64_t h) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

std::string digestText(uint64_t digest) {
    char b[32];
    std::snprintf(b, sizeof b, "fnv1a64:%016llx", static_cast<unsigned long long>(digest));
    return b;
}

std::string imageDigest(const HostImage& image) {
    return digestText(fnv1a64(image.pixels.data(), image.pixels.size() * sizeof(float)));
}

}  // namespace cavity::core