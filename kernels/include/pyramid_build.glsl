// Building the linear-depth pyramid in one dispatch (depth_pyramid_single.glsl
// says how): the thread of a level-0 texel writes it to every smaller level
// whose texel picked it. Included by depth_pyramid_single.glsl and by
// downsample_pyramid.glsl, which makes level 0 itself at half resolution.
// The including kernel has a one-dispatch mip output named zmip
// (OutputDecl::oneDispatch, so write_zmip_level) of frame.size.
#include "include/pyramid_texel.glsl"

ivec2 levelSizeOf(int l) {
    return max(frame.size >> l, ivec2(1));
}

#if CAVITY_LEVELS_zmip > 16
#error the one-dispatch pyramid writes at most 16 levels: add links to writePyramidChain
#endif

// Link k of this pixel's chain: whether texel pixel >> k of level k picked
// it, and if so that texel written. A pixel no texel of level k picked is
// picked by no smaller level either (the chain passes through level k), and
// neither is one past an odd level's last texel: the first false ends the
// work. Three pixels in four stop at level 1.
bool pyramidLink(int k, ivec2 pixel, vec4 depth) {
    if (k >= CAVITY_LEVELS_zmip) return false;
    ivec2 t = pixel >> k;
    if (any(greaterThanEqual(t, levelSizeOf(k)))) return false;
    ivec2 pick = min(t * 2 + ivec2(t.y & 1, t.x & 1), levelSizeOf(k - 1) - 1);
    if (pick != pixel >> (k - 1)) return false;
    write_zmip_level(k, t, depth);
    return true;
}

// Level 0's texel `pixel`, its pyramidValue `depth`, written to every level
// whose texel picked it (level 0 itself is the caller's).
void writePyramidChain(ivec2 pixel, vec4 depth) {
    // The links written out, each with its level a constant, where a loop
    // over k was one: NVIDIA's GL driver kept that loop rolled, picking the
    // level's image through a chain of tests every iteration, and this form
    // made the pass faster there (Vulkan unrolled it already; study
    // 2026-12-03_h200_unroll).
    if (!pyramidLink(1, pixel, depth)) return;
    if (!pyramidLink(2, pixel, depth)) return;
    if (!pyramidLink(3, pixel, depth)) return;
    if (!pyramidLink(4, pixel, depth)) return;
    if (!pyramidLink(5, pixel, depth)) return;
    if (!pyramidLink(6, pixel, depth)) return;
    if (!pyramidLink(7, pixel, depth)) return;
    if (!pyramidLink(8, pixel, depth)) return;
    if (!pyramidLink(9, pixel, depth)) return;
    if (!pyramidLink(10, pixel, depth)) return;
    if (!pyramidLink(11, pixel, depth)) return;
    if (!pyramidLink(12, pixel, depth)) return;
    if (!pyramidLink(13, pixel, depth)) return;
    if (!pyramidLink(14, pixel, depth)) return;
    pyramidLink(15, pixel, depth);
}
