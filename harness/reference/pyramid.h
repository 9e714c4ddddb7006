// The CPU side of kernels/include/pyramid.glsl and octahedral.glsl, shared by
// the fast variants' references (ref_fast.cpp defines them; ref_ssdo.cpp's
// ssdo_fast uses them too). Operation for operation where a value picks a
// texel or decides a test.
#pragma once

#include "reference/namespace.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

namespace cavity::reference::pyramid {

// positionAt(): view position on the ray through the centre of (x, y) at
// linear depth `depth`.
Vec3 positionAt(const kernels::FrameUniforms& f, int x, int y, float depth);

// cavityLayerTexel(): where pixel (x, y) lies in the atlas of k x k
// interleaved layers of a pass of f's size (OutputDecl::layered).
inline std::pair<int, int> layerTexel(const kernels::FrameUniforms& f, int k, int x, int y) {
    const int lw = (f.size[0] + k - 1) / k, lh = (f.size[1] + k - 1) / k;
    return {x % k * lw + x / k, y % k * lh + y / k};
}

// The levels of depth_pyramid's output.
int levelCount();

// include/pyramid_texel.glsl's PYRAMID_OFFSET_BITS: the source pixel's
// offset bits per axis a texel packs below its depth.
inline constexpr int kOffsetBits = 5;

// pyramidValue(): the texel of `level` whose depth came from level-0 pixel
// (sx, sy), the pixel's offset in its block packed into the depth's low
// bits; the background (depth <= 0) as it is.
inline float packValue(float depth, int sx, int sy, int level) {
    const int n = std::min(level, kOffsetBits), drop = level - n;
    const int32_t ox = (sx & ((1 << level) - 1)) >> drop, oy = (sy & ((1 << level) - 1)) >> drop;
    const int32_t bits = (std::bit_cast<int32_t>(depth) & ~((int32_t(1) << (2 * n)) - 1)) | ox | (oy << n);
    return depth > 0.0f ? std::bit_cast<float>(bits) : depth;
}

// pyramidSourceOf(): the level-0 pixel whose depth texel (tx, ty) of
// `level` holds (`packed`), into (tx, ty).
inline void sourceOf(float packed, int level, int& tx, int& ty) {
    const int n = std::min(level, kOffsetBits);
    const int32_t bits = std::bit_cast<int32_t>(packed), mask = (int32_t(1) << n) - 1;
    tx = (tx << level) | ((bits & mask) << (level - n));
    ty = (ty << level) | (((bits >> n) & mask) << (level - n));
}

// The level-0 pixel whose depth texel (tx, ty) of `level` holds, read from
// the texel's bits as the GPU reads it (sourceOf). Every depth a fast
// kernel reads off the pyramid passes through here, so it also counts the
// read in levelReads().
void sourcePixel(const std::vector<HostImage>& zmip, int level, int& tx, int& ty);

// The same pixel found by undoing the picks: the build's rule stated a
// second way (pyramidLevels packs what it finds, and the GPU's builds are
// held to that). Reads the levels' sizes only.
void undoPicks(const std::vector<HostImage>& zmip, int level, int& tx, int& ty);

// How many depths the references have read from each pyramid level since
// the last reset: which code paths of the fast kernels a configuration
// reaches (the deep levels only when samples land far from their pixel, at
// large sizes or radii). Counted per thread.
std::vector<long long>& levelReads();

// PyramidView and pyramidView().
struct View {
    float toPixelX, toPixelY, centreX, centreY;
    int maxLevel;
};
View view(const kernels::FrameUniforms& f, int levels);

// pyramidLookup(): the stored surface under the view point s, seen from
// (x, y): false off the screen, behind the camera or on the background;
// (sx, sy) and zq the level-0 pixel and depth it holds.
bool lookup(const kernels::FrameUniforms& f, const std::vector<HostImage>& zmip, const View& v, Vec3 s, int x, int y,
            int& sx, int& sy, float& zq);

// pyramidBlocks(): whether the view point s, sampled from the receiver at
// pixel (x, y) with unit normal N and level N . X, is blocked by the stored
// point lookup() finds.
bool blocks(const kernels::FrameUniforms& f, const std::vector<HostImage>& zmip, const View& v, Vec3 N,
            float receiverLevel, Vec3 s, int x, int y, float bias, int& sx, int& sy, float& zq);

Vec2 octEncode(Vec3 n);
Vec3 octDecode(float px, float py);

}  // namespace cavity::reference::pyramid
