// The linear-depth pyramid on the CPU (kernels/passes/depth_pyramid/depth_pyramid.glsl): its
// levels rebuilt from level 0, each texel's source pixel found by undoing
// the picks, and the count of reads per level that the fast kernels'
// references make through sourcePixel().
#include "reference/pyramid.h"
#include "reference/reference.h"
#include "reference/refs.h"

#include <algorithm>

namespace cavity::reference {

namespace pyramid {

int levelCount() {
    const auto* k = kernels::find("depth_pyramid");
    return k && !k->outputs.empty() ? k->outputs[0].mipLevels : 1;
}

std::vector<long long>& levelReads() {
    thread_local std::vector<long long> reads;
    return reads;
}

void packSources(HostImage& level0) {
    for (int y = 0; y < level0.height; ++y)
        for (int x = 0; x < level0.width; ++x) level0.at(x, y, 1) = packSource(x, y);
}

// The pyramid's picks, undone one level at a time.
void sourcePixel(const std::vector<HostImage>& zmip, int level, int& tx, int& ty) {
    auto& reads = levelReads();
    if (reads.size() <= size_t(level)) reads.resize(size_t(level) + 1, 0);
    ++reads[size_t(level)];
    undoPicks(zmip, level, tx, ty);
}

void undoPicks(const std::vector<HostImage>& zmip, int level, int& tx, int& ty) {
    for (int k = level; k > 0; --k) {
        const HostImage& above = zmip[size_t(k - 1)];
        const int px = std::min(2 * tx + (ty & 1), above.width - 1);
        ty = std::min(2 * ty + (tx & 1), above.height - 1);
        tx = px;
    }
}

}  // namespace pyramid

std::vector<HostImage> pyramidLevels(const HostImage& level0, int levels) {
    std::vector<HostImage> chain;
    HostImage first(level0.width, level0.height, 2);
    for (int y = 0; y < level0.height; ++y)
        for (int x = 0; x < level0.width; ++x) first.at(x, y) = level0.at(x, y);
    pyramid::packSources(first);
    chain.push_back(std::move(first));
    for (int l = 1; l < levels; ++l) {
        const HostImage& above = chain.back();
        HostImage next(std::max(1, level0.width >> l), std::max(1, level0.height >> l), 2);
        for (int y = 0; y < next.height; ++y)
            for (int x = 0; x < next.width; ++x) {
                next.at(x, y) = above.at(std::min(2 * x + (y & 1), above.width - 1),
                                         std::min(2 * y + (x & 1), above.height - 1));
                // The source pixel by undoing the picks all the way down,
                // not copied along them as the builds do: the second
                // statement of the rule that the builds' is checked against.
                int sx = x, sy = y;
                pyramid::undoPicks(chain, l, sx, sy);   // reads levels 0 .. l - 1 only
                next.at(x, y, 1) = pyramid::packSource(sx, sy);
            }
        chain.push_back(std::move(next));
    }
    return chain;
}

}  // namespace cavity::reference
