// Reading the linear-depth pyramid (depth_pyramid.glsl): the fast AO
// kernels' shared helpers, mirrored by harness/reference/ref_fast.cpp.
#include "include/common.glsl"

// Samples up to 2^(3 + 1) = 16 px away read level 0; each doubling of the
// distance moves one level down (after Scalable Ambient Obscurance).
const int LOG_MAX_OFFSET = 3;

// viewRayAt(pixel) * depth with each operation rounded as the CPU's is: the
// rebuilt positions feed discrete decisions (a radius or a depth test).
vec3 positionAt(ivec2 pixel, float depth) {
    precise vec2 ndc = (vec2(pixel) + 0.5) * frame.invSize * 2.0 - 1.0;
    precise vec3 p = vec3(ndc.x * frame.camera.x * depth, -ndc.y * frame.camera.y * depth, -depth);
    return p;
}

// The size of pyramid level l: level 0 is this pass's size, and each mip
// halves it, rounding down. Not textureSize(in_zmip, l): llvmpipe answers that
// query with one lane's lod for every lane when l varies across them, which
// clamped samples of level-0 pixels into a neighbour's level-1 size.
ivec2 levelSize(int l) {
    return max(frame.size >> l, ivec2(1));
}

// The level a sample `h` pixels from its receiver reads (h >= 0).
int pyramidLevel(int h, int maxLevel) {
    return clamp(findMSB(h) - LOG_MAX_OFFSET, 0, maxLevel);
}

// The level-0 pixel whose depth texel t of `level` holds: undoes
// depth_pyramid.glsl's pick (2x + (y & 1), 2y + (x & 1)) once per level. The
// pick appends one bit to each coordinate per level, and the bits it appends
// alternate: to x the parity of y, then of x, then of y...; to y the other
// way round. So the whole chain is a shift and two masks, where a loop over
// the levels cost a sixth of the pass on the H200 (bench/ROOFLINE.md). The
// clamp into a level above never acts while that level is at least 2 texels
// across (t < floor(s / 2) gives 2t + 1 < s); the loop stays for the 1-texel
// levels of tiny images, the only ones where it does.
ivec2 sourcePixel(ivec2 t, int level) {
    if (level == 0) return t;
    if (any(lessThanEqual(frame.size >> (level - 1), ivec2(1)))) {
        for (int k = level; k > 0; --k) t = min(t * 2 + ivec2(t.y & 1, t.x & 1), levelSize(k - 1) - 1);
        return t;
    }
    int high = int(0xAAAAAAAAu >> uint(32 - level));   // bits level-1, level-3, ...
    int low = ((1 << level) - 1) ^ high;                // bits level-2, level-4, ...
    ivec2 parity = t & 1;
    return (t << level) | ivec2(parity.y * high | parity.x * low, parity.x * high | parity.y * low);
}
