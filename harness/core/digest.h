// Digests.
//
// Images are named by SHA-256 (OpenSSL's libcrypto) of their pixels: the
// digest approvals.json, the image store and every render folder record. A
// store that anyone can write to must not accept a forged image under an
// approved name, and a non-cryptographic hash allows one to be made at will.
// Images approved before SHA-256 carry FNV-1a 64 digests ("fnv1a64:"); they
// are still read (and warned about) until `cavity baselines migrate-digests`
// rewrites them (docs/store.md, "Digests").
//
// FNV-1a 64 stays where only accidents are guarded against: the matrix
// declaration's hash, a kernel edit's text, a history file's key.
#pragma once

#include "core/image.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace cavity::core {

uint64_t fnv1a64(const void* data, size_t size, uint64_t seed = 14695981039346656037ull);
// "fnv1a64:" and 16 lower-case hex digits.
std::string digestText(uint64_t digest);

// "sha256:" and 64 lower-case hex digits, of the pixels' bytes as
// little-endian float32, row after row, top to bottom.
std::string imageDigest(const HostImage& image);
// The same bytes' FNV-1a 64 ("fnv1a64:..."): the digest of images approved
// before SHA-256.
std::string legacyImageDigest(const HostImage& image);
// The image's digest in the algorithm `like` is written in (sha256: or
// fnv1a64:), to check an image against a digest of either kind.
std::string imageDigestLike(const HostImage& image, const std::string& like);

// Is `digest` one of the two forms, exactly (prefix, length, lower-case hex)?
bool isImageDigest(const std::string& digest);
bool isLegacyDigest(const std::string& digest);   // an image digest in fnv1a64:

// The bytes as base64 (RFC 4648, with padding), by OpenSSL's EVP_EncodeBlock:
// images inlined in a self-contained page.
std::string base64(const std::string& bytes);

}  // namespace cavity::core
