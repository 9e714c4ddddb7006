// One image of a render folder, in the format "cavity.f32z/1": the exact
// float32 pixels the GPU read back, losslessly, readable with zlib alone
// (no OpenImageIO on the GPU machine, see docs/gpu.md).
//
//   bytes  0..7   magic "CAVF32Z1"
//          8..11  width, 12..15 height, 16..19 channels (uint32, little-endian)
//         20..23  bytes per stored sample: 4 float32; 2 float16, when every
//                 value is exactly a half float; 1 a palette index, when the
//                 image has at most 256 distinct values
//         24..31  stored byte count (uint64): samples x bytes per sample,
//                 plus 1024 for the palette
//         32..    one zlib stream of the stored bytes, to the end of the file
//
// Samples are HostImage::pixels in order (channels interleaved, rows top to
// bottom), little-endian. Float32 and float16 samples are byte-shuffled:
// byte 0 of every sample, then byte 1, and so on (HDF5's shuffle filter: the
// slowly varying sign and exponent bytes end up next to each other). With a
// palette the stream is 256 float32 values (sorted by their bits, unused
// ones zero), then one index byte per sample. The kernels write R16F and
// RGBA8 targets, so AO is stored as float16 and colour with a palette, each
// only after checking that it gives back the same float32 bits; anything
// else stays float32. Decoding gives back the very bits, and the digest says so.
#pragma once

#include "render/namespace.h"
#include "core/image.h"
#include "result.h"

#include <cstdint>
#include <string>

namespace cavity::render {

constexpr const char* kImageFormat = "cavity.f32z/1";
constexpr size_t kImageHeaderBytes = 32;

// What the manifest says about a stored image, for readImageFile to check.
struct StoredImage {
    int width = 0, height = 0, channels = 0;
    std::string digest;      // digest.h imageDigest() of the pixels
    uint64_t bytes = 0;      // the file's size
};

// The file's bytes.
// `level`: zlib's, 1 (fast) to 9 (small); render folders use 6.
std::string encodeImage(const HostImage& image, int level = 6);
// Writes through a temporary name and a rename; returns the file's size.
Result<uint64_t> writeImageFile(const std::string& path, const HostImage& image, int level = 6);
// Reads and checks against `expect`, in the order a damaged file is best
// described: missing, shorter than a header, not this format, another
// shape, truncated or longer than recorded, a zlib stream that does not
// inflate to exactly the raw byte count, a digest other than recorded.
// Every message starts with "PATH: ".
Result<HostImage> readImageFile(const std::string& path, const StoredImage& expect);
// Decodes the bytes of one image file, checking the format's own
// consistency (header, sizes, the zlib stream) but no digest; messages start
// with "LABEL: ".
Result<HostImage> decodeImage(const std::string& bytes, const std::string& label);

}  // namespace cavity::render
