#include "core/digest.h"

#include <openssl/evp.h>

#include <algorithm>
#include <bit>
#include <cstdio>

namespace cavity::core {

// The digest is of the little-endian bytes; hashing memory as it lies is
// only that on a little-endian machine (every machine Cavity runs on).
static_assert(std::endian::native == std::endian::little, "image digests assume a little-endian host");

namespace {

constexpr const char* kSha256 = "sha256:";
constexpr const char* kFnv = "fnv1a64:";

bool hexTail(const std::string& s, const std::string& prefix, size_t digits) {
    if (s.size() != prefix.size() + digits || s.compare(0, prefix.size(), prefix) != 0) return false;
    for (size_t i = prefix.size(); i < s.size(); ++i)
        if (!((s[i] >= '0' && s[i] <= '9') || (s[i] >= 'a' && s[i] <= 'f'))) return false;
    return true;
}

}  // namespace

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
    std::snprintf(b, sizeof b, "%s%016llx", kFnv, static_cast<unsigned long long>(digest));
    return b;
}

std::string imageDigest(const HostImage& image) {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    // EVP_Digest fails only when out of memory or without SHA-256 (a FIPS
    // provider that lacks it); an empty digest then matches nothing.
    if (EVP_Digest(image.pixels.data(), image.pixels.size() * sizeof(float), md, &size, EVP_sha256(), nullptr) != 1)
        return "";
    std::string text = kSha256;
    static const char* hex = "0123456789abcdef";
    for (unsigned int i = 0; i < size; ++i) {
        text += hex[md[i] >> 4];
        text += hex[md[i] & 15];
    }
    return text;
}

std::string legacyImageDigest(const HostImage& image) {
    return digestText(fnv1a64(image.pixels.data(), image.pixels.size() * sizeof(float)));
}

std::string imageDigestLike(const HostImage& image, const std::string& like) {
    return isLegacyDigest(like) ? legacyImageDigest(image) : imageDigest(image);
}

bool isImageDigest(const std::string& digest) { return hexTail(digest, kSha256, 64) || isLegacyDigest(digest); }

bool isLegacyDigest(const std::string& digest) { return hexTail(digest, kFnv, 16); }

std::string base64(const std::string& bytes) {
    std::string out(4 * ((bytes.size() + 2) / 3) + 1, '\0');
    const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                  reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()));
    out.resize(size_t(std::max(n, 0)));
    return out;
}

}  // namespace cavity::core
