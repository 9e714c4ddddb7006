#include "render/image_file.h"

#include "core/digest.h"
#include "core/json_file.h"
#include "texels/texels.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include <unistd.h>

namespace cavity::render {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'C', 'A', 'V', 'F', '3', '2', 'Z', '1'};
// zlib's default level: on 1920x1080 renders level 1 was faster but gave
// files 1.4x larger (colour 1.6x); the GPU machine's upload is the scarcer
// resource (README.md, "Why this image format").

void putU32(std::string& s, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) s[at + i] = char(v >> (8 * i) & 0xff);
}
void putU64(std::string& s, size_t at, uint64_t v) {
    for (int i = 0; i < 8; ++i) s[at + i] = char(v >> (8 * i) & 0xff);
}
uint32_t getU32(const std::string& s, size_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(uint8_t(s[at + i])) << (8 * i);
    return v;
}
uint64_t getU64(const std::string& s, size_t at) {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(uint8_t(s[at + i])) << (8 * i);
    return v;
}

// The half float with exactly the value of f, if there is one. NaNs are
// left to float32: their payloads need not survive.
bool exactHalf(float f, uint16_t& h) {
    if (std::isnan(f)) return false;
    h = gpu::texels::toHalf(f);
    return std::bit_cast<uint32_t>(gpu::texels::fromHalf(h)) == std::bit_cast<uint32_t>(f);
}

constexpr size_t kPaletteBytes = 256 * 4;

// At most 256 distinct values (bit patterns): a palette of them, sorted by
// bits, and one index byte per sample. Colour read back from an RGBA8 target
// is that, however the driver converts k to a float (lavapipe as k / 255.0f,
// llvmpipe's GL as k * (1.0f / 255.0f): they differ in the last bit).
bool palette(const HostImage& image, std::string& out) {
    std::vector<uint32_t> values;
    uint32_t last = 0;
    bool any = false;
    for (float f : image.pixels) {
        const uint32_t v = std::bit_cast<uint32_t>(f);
        if (any && v == last) continue;   // runs along a row are the common case
        any = true;
        last = v;
        const auto at = std::lower_bound(values.begin(), values.end(), v);
        if (at != values.end() && *at == v) continue;
        if (values.size() == 256) return false;
        values.insert(at, v);
    }
    const size_t n = image.pixels.size();
    out.assign(kPaletteBytes + n, '\0');
    for (size_t i = 0; i < values.size(); ++i)
        for (size_t b = 0; b < 4; ++b) out[4 * i + b] = char(values[i] >> (8 * b) & 0xff);
    size_t index = 0;
    last = values.empty() ? 0 : values[0];
    for (size_t i = 0; i < n; ++i) {
        const uint32_t v = std::bit_cast<uint32_t>(image.pixels[i]);
        if (v != last) {
            index = size_t(std::lower_bound(values.begin(), values.end(), v) - values.begin());
            last = v;
        }
        out[kPaletteBytes + i] = char(index);
    }
    return true;
}

// The narrowest exact storage of the image's samples: a palette and 1 byte
// each, or 2 or 4 bytes each, byte-shuffled.
std::string narrowest(const HostImage& image, uint32_t& sampleBytes) {
    const size_t n = image.pixels.size();
    std::string out;
    if (palette(image, out)) {
        sampleBytes = 1;
        return out;
    }
    out.assign(2 * n, '\0');
    bool ok = true;
    for (size_t i = 0; i < n && ok; ++i) {
        uint16_t h = 0;
        ok = exactHalf(image.pixels[i], h);
        out[i] = char(h & 0xff);
        out[n + i] = char(h >> 8);
    }
    if (ok) {
        sampleBytes = 2;
        return out;
    }
    out.assign(4 * n, '\0');
    for (size_t i = 0; i < n; ++i) {
        const uint32_t bits = std::bit_cast<uint32_t>(image.pixels[i]);
        for (size_t b = 0; b < 4; ++b) out[b * n + i] = char(bits >> (8 * b) & 0xff);
    }
    sampleBytes = 4;
    return out;
}

uint64_t storedBytes(uint64_t samples, uint32_t sampleBytes) {
    return samples * sampleBytes + (sampleBytes == 1 ? kPaletteBytes : 0);
}

void widen(const std::string& stored, uint32_t sampleBytes, HostImage& image) {
    const size_t n = image.pixels.size();
    const auto byte = [&](size_t at) { return uint32_t(uint8_t(stored[at])); };
    for (size_t i = 0; i < n; ++i) {
        if (sampleBytes == 1) {
            const size_t p = 4 * byte(kPaletteBytes + i);
            image.pixels[i] = std::bit_cast<float>(byte(p) | byte(p + 1) << 8 | byte(p + 2) << 16 | byte(p + 3) << 24);
        } else if (sampleBytes == 2) {
            image.pixels[i] = gpu::texels::fromHalf(uint16_t(byte(i) | byte(n + i) << 8));
        } else {
            image.pixels[i] = std::bit_cast<float>(byte(i) | byte(n + i) << 8 | byte(2 * n + i) << 16 | byte(3 * n + i) << 24);
        }
    }
}

std::string shapeOf(uint64_t w, uint64_t h, uint64_t c) {
    return std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c);
}

}  // namespace

std::string encodeImage(const HostImage& image, int level) {
    uint32_t sampleBytes = 4;
    const std::string raw = narrowest(image, sampleBytes);
    uLongf packed = compressBound(uLong(raw.size()));
    std::string out(kImageHeaderBytes + packed, '\0');
    std::memcpy(out.data(), kMagic, sizeof kMagic);
    putU32(out, 8, uint32_t(image.width));
    putU32(out, 12, uint32_t(image.height));
    putU32(out, 16, uint32_t(image.channels));
    putU32(out, 20, sampleBytes);
    putU64(out, 24, raw.size());
    // compress2 only fails for lack of memory or a too small buffer, and
    // compressBound() is large enough by definition.
    compress2(reinterpret_cast<Bytef*>(out.data() + kImageHeaderBytes), &packed,
              reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), level);
    out.resize(kImageHeaderBytes + packed);
    return out;
}

Result<uint64_t> writeImageFile(const std::string& path, const HostImage& image, int level) {
    const std::string bytes = encodeImage(image, level);
    core::removeStaleTemps(fs::path(path).parent_path().string());
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) return badInput(path + ": cannot write");
        f.write(bytes.data(), std::streamsize(bytes.size()));
        if (!f) return internal("write " + path + " failed (disk full?)");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) return internal("rename " + tmp + " -> " + path + ": " + ec.message());
    return uint64_t(bytes.size());
}

namespace {

// The checks of readImageFile() on bytes already read, in its order;
// without `expect` (a store object), only the format's own consistency.
Result<HostImage> decode(const std::string& data, const std::string& path, const StoredImage* expect) {
    const std::string recorded = expect ? ", the manifest says " + std::to_string(expect->bytes) : std::string();
    if (data.size() < kImageHeaderBytes)
        return badInput(path + ": truncated: " + std::to_string(data.size()) + " bytes" + recorded);
    if (std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
        return badInput(path + ": not a " + std::string(kImageFormat) + " image (no CAVF32Z1 header)");
    const uint32_t w = getU32(data, 8), h = getU32(data, 12), c = getU32(data, 16);
    if (expect && (int64_t(w) != expect->width || int64_t(h) != expect->height || int64_t(c) != expect->channels))
        return badInput(path + ": wrong size: the file is " + shapeOf(w, h, c) + ", the manifest says " +
                        shapeOf(uint64_t(expect->width), uint64_t(expect->height), uint64_t(expect->channels)));
    if (!expect && (w == 0 || h == 0 || c == 0 || c > 4 || uint64_t(w) * h > (uint64_t(1) << 28)))
        return badInput(path + ": corrupt header: " + shapeOf(w, h, c));
    const uint32_t sampleBytes = getU32(data, 20);
    if (sampleBytes != 1 && sampleBytes != 2 && sampleBytes != 4)
        return badInput(path + ": corrupt header: " + std::to_string(sampleBytes) + " bytes per sample (1, 2 or 4)");
    const uint64_t raw = storedBytes(uint64_t(w) * h * c, sampleBytes);
    if (getU64(data, 24) != raw)
        return badInput(path + ": corrupt header: stored size " + std::to_string(getU64(data, 24)) + " for " +
                        shapeOf(w, h, c) + " at " + std::to_string(sampleBytes) + " bytes (" + std::to_string(raw) + ")");
    if (expect && data.size() < expect->bytes)
        return badInput(path + ": truncated: " + std::to_string(data.size()) + " bytes" + recorded);
    if (expect && data.size() > expect->bytes)
        return badInput(path + ": " + std::to_string(data.size()) + " bytes" + recorded + " (appended to?)");
    if (raw > std::numeric_limits<uLong>::max()) return badInput(path + ": image too large for zlib here");
    std::string planes(raw, '\0');
    uLongf outLen = uLongf(raw);
    uLong inLen = uLong(data.size() - kImageHeaderBytes);
    const int z = uncompress2(reinterpret_cast<Bytef*>(planes.data()), &outLen,
                              reinterpret_cast<const Bytef*>(data.data() + kImageHeaderBytes), &inLen);
    if (z != Z_OK || outLen != raw || inLen != data.size() - kImageHeaderBytes)
        return badInput(path + ": corrupt: the zlib stream " +
                        (z == Z_OK ? std::string("does not end where the file does")
                                   : std::string("does not inflate (") + zError(z) + ")"));
    HostImage image{int(w), int(h), int(c)};
    widen(planes, sampleBytes, image);
    if (expect) {
        const std::string digest = core::imageDigestLike(image, expect->digest);
        if (digest != expect->digest)
            return badInput(path + ": corrupt: digest " + digest + ", the manifest says " + expect->digest);
    }
    return image;
}

}  // namespace

Result<HostImage> decodeImage(const std::string& bytes, const std::string& label) {
    return decode(bytes, label, nullptr);
}

Result<HostImage> readImageFile(const std::string& path, const StoredImage& expect) {
    // A folder opens as a stream on Linux, and reading it throws from inside
    // libstdc++ (EISDIR): only a regular file is read.
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        return badInput(path + ": not a file (the manifest lists an image file here)");
    std::ifstream f(path, std::ios::binary);
    if (!f) return badInput(path + ": missing or unreadable (the manifest lists it)");
    const std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    return decode(data, path, &expect);
}

}  // namespace cavity::render
