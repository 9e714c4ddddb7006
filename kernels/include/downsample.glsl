// The depth-aware 2x2 downsample's pick (downsample_depth.glsl says which
// texel and why), shared by downsample_depth.glsl and downsample_pyramid.glsl.
// frame.size is the half size; the full size is in_position's own.
#include "include/screen_space.glsl"

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
    for (int k = 1; k < 4; ++k) {
        ivec2 texel = min(pixel * 2 + ivec2(k & 1, k >> 1), full - 1);
        float d = blockDepth(texelFetch(in_position, texel, 0));
        if (nearest ? d < bestDepth : d > bestDepth) {
            best = texel;
            bestDepth = d;
        }
    }
    return best;
}

// The linear depth at which half texel `pixel`'s own centre ray meets the
// tangent plane of the full texel it copies (position p, normal n). The
// fast kernels rebuild every position from the pyramid's depth on the half
// texel's ray; with the copied depth, which lies on the full texel's ray
// half a full texel away, the rebuilt floor of an open scene stood in front
// of and behind itself from texel to texel, and its samples read as
// occluded: a speckled grey over open floors, the worse the smaller the
// image (the effect depth_from_position_half.glsl removes for the hardware
// depth). A move of over a twentieth of the depth (a plane nearly edge-on
// to the ray) keeps the copied depth.
float halfRayDepth(ivec2 pixel, vec4 p, vec3 n) {
    if (isBackground(p.w)) return p.w;
    vec3 hit;
    // -hit.z is t exactly (ray.z = -1).
    return halfTexelRayHit(pixel, p.xyz, n, hit) ? -hit.z : p.w;
}
