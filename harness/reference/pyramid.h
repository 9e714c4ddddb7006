// The CPU side of kernels/include/pyramid.glsl and octahedral.glsl, shared by
// the fast variants' references (ref_fast.cpp defines them; ref_ssdo.cpp's
// ssdo_fast uses them too). Operation for operation where a value picks a
// texel or decides a test.
#pragma once

#include "reference/namespace.h"
#include "reference/refs.h"
#include "reference/vec.h"

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

// pyramidValue()'s second channel (include/pyramid_texel.glsl): the level-0
// pixel (x, y) a texel's depth came from, its bits as they are.
inline float packSource(int x, int y) {
    return std::bit_cast<float>(int32_t(0x40000000 | (y << 15) | x));
}

// A level-0 image of the pyramid (depth in channel 0, two channels, as a
// build writes it): each pixel's own packSource in channel 1.
void packSources(HostImage& level0);

// The level-0 pixel whose depth texel (tx, ty) of `level` holds, found by
// undoing the picks: the readers' statement of the rule, where the GPU reads
// the pixel the build stored. Every depth a fast kernel reads off the
// pyramid passes through here, so it also counts the read in levelReads().
void sourcePixel(const std::vector<HostImage>& zmip, int level, int& tx, int& ty);

// The same, without counting.
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
