// FNV-1a 64 over bytes: the digest a render folder records for every image
// (of its raw float32 pixels) and for the matrix it rendered (of the
// declaration's JSON text). Not cryptographic; it is there to catch a wrong,
// stale or damaged file, not a forged one.
#pragma once

#include "core/image.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace cavity::core {

uint64_t fnv1a64(const void* data, size_t size, uint64_t seed = 14695981039346656037ull);
// "fnv1a64:" and 16 lower-case hex digits.
std::string digestText(uint64_t digest);
// Of the pixels' bytes as little-endian float32, row after row, top to bottom.
std::string imageDigest(const HostImage& image);

}  // namespace cavity::core