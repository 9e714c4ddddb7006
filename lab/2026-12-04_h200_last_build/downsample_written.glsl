// The depth-aware 2x2 downsample's pick (downsample_depth.glsl says which
// texel and why), shared by downsample_depth.glsl and downsample_pyramid.glsl.
// frame.size is the half size; the full size is in_position's own.
#include "include/common.glsl"

// Background (w = 0) counts as infinitely far, so it wins the max.
float blockDepth(vec4 p) {
    return isBackground(p.w) ? 3.0e38 : p.w;
}

// The full-resolution texel half texel `pixel` copies.
ivec2 downsamplePick(ivec2 pixel) {
    ivec2 full = textureSize(in_position, 0);
    bool nearest = ((pixel.x + pixel.y) & 1) == 0;
    ivec2 best = min(pixel * 2, full - 1);
    float bestDepth = blockDepth(texelFetch(in_position, best, 0));
    // Fixed order and strict comparisons: ties keep the first texel, on the
    // GPU and in the reference alike. Odd full sizes clamp the last block.
    // PROBE: the three texels written out.
#define DOWNSAMPLE_TEXEL(k) { \
        ivec2 texel = min(pixel * 2 + ivec2((k) & 1, (k) >> 1), full - 1); \
        float d = blockDepth(texelFetch(in_position, texel, 0)); \
        if (nearest ? d < bestDepth : d > bestDepth) { \
            best = texel; \
            bestDepth = d; \
        } \
    }
    DOWNSAMPLE_TEXEL(1)
    DOWNSAMPLE_TEXEL(2)
    DOWNSAMPLE_TEXEL(3)
    return best;
}
