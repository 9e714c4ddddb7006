// Study variant (lab 2026-12-06_gpu_half_tail), in place of
// include/upsample.glsl: the joint bilateral upsample without its normal
// term, so the half-resolution normal is never read. Below, the original.
// The joint bilateral upsample of half-resolution AO, shared by
// upsample_bilateral.glsl (its own pass) and upsample_composite.glsl (the
// fused half-resolution tail). A kernel that includes it declares the
// inputs ao_half, position_half and normal_half and the parameter
// upsample_depth_tolerance. Each full-resolution pixel blends the 4 half
// texels around it with
//
//     w_i = bilinear_i * exp(-0.5 * (|N . (Q_i - P)| / (tol * z))^2) * max(0, N . N_i)^8
//
// P, N, z: the full pixel's view position, normal and linear depth; Q_i, N_i:
// half texel i's (copied by downsample_depth, so real surface points);
// tol: P.upsample_depth_tolerance. The depth term measures Q_i's distance
// from P's tangent plane rather than the plain depth difference: on a floor
// seen at a grazing angle depth changes fast from texel to texel though the
// surface is one plane, and the plane distance is 0 there at any slope. It is
// relative to z because the texel footprint grows with depth. The normal
// term keeps a floor from borrowing a wall's AO at a crease, where the plane
// distance is small. If every weight vanishes (a pixel whose surface no half
// texel kept), the half texel nearest in depth is taken as it is.
#include "include/screen_space.glsl"

// The compute pass's tile: the half texels the workgroup's pixels blend,
// each fetched once (AO, position, normal: three fetches) where each of the
// 4 pixels over it fetched it again. A workgroup of W x H pixels (both even)
// blends W/2 + 2 x H/2 + 2 half texels, starting one texel up and left of
// its own; each is clamped to the image as upsampleAo() clamps it. The
// kernel declares wholeWorkgroups: every invocation loads and meets at the
// barrier. An odd workgroup side, and the fragment stage, take the texture
// path.
#ifdef CAVITY_STAGE_COMPUTE
#if CAVITY_WORKGROUP_X % 2 == 0 && CAVITY_WORKGROUP_Y % 2 == 0
#define UPSAMPLE_TILED 1
const int kHalfTileW = CAVITY_WORKGROUP_X / 2 + 2;
const int kHalfTileH = CAVITY_WORKGROUP_Y / 2 + 2;
shared float tileHalfAo[kHalfTileW * kHalfTileH];
shared vec4 tileHalfPosition[kHalfTileW * kHalfTileH];

ivec2 halfTileOrigin() {
    return ivec2(gl_WorkGroupID.xy) * ivec2(CAVITY_WORKGROUP_X / 2, CAVITY_WORKGROUP_Y / 2) - 1;
}
#endif
#endif

// Every invocation of the workgroup calls this first, also those past the
// image's edge; it does nothing where there is no tile.
void upsampleShareTile() {
#ifdef UPSAMPLE_TILED
    ivec2 halfSize = textureSize(in_ao_half, 0);
    for (int i = int(gl_LocalInvocationIndex); i < kHalfTileW * kHalfTileH; i += CAVITY_WORKGROUP_X * CAVITY_WORKGROUP_Y) {
        ivec2 texel = clamp(halfTileOrigin() + ivec2(i % kHalfTileW, i / kHalfTileW), ivec2(0), halfSize - 1);
        tileHalfAo[i] = texelFetch(in_ao_half, texel, 0).r;
        tileHalfPosition[i] = texelFetch(in_position_half, texel, 0);
    }
    barrier();
#endif
}

// p: the pixel's view position (w: linear depth), nrm its normal; the pixel
// is a surface (not background, a non-zero normal). Call upsampleShareTile()
// before.
float upsampleAo(ivec2 pixel, vec4 p, vec3 nrm) {
#ifndef UPSAMPLE_TILED
    ivec2 halfSize = textureSize(in_ao_half, 0);
#endif
    // The full pixel centre (pixel + 0.5) in half-texel units, minus the half
    // texel centre offset: pixel / 2 - 0.25, exact in float.
    vec2 c = vec2(pixel) * 0.5 - 0.25;
    ivec2 base = ivec2(floor(c));
    vec2 f = c - vec2(base);
    float tol = P.upsample_depth_tolerance * p.w;

    float sum = 0.0, weightSum = 0.0;
    float fallback = 1.0, fallbackDist = 3.0e38;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
#ifdef UPSAMPLE_TILED
        ivec2 t = base + o - halfTileOrigin();
        int i = t.y * kHalfTileW + t.x;
        float ao = tileHalfAo[i];
        vec4 q = tileHalfPosition[i];
#else
        ivec2 texel = clamp(base + o, ivec2(0), halfSize - 1);
        float ao = texelFetch(in_ao_half, texel, 0).r;
        vec4 q = texelFetch(in_position_half, texel, 0);
#endif
        if (isBackground(q.w)) continue;   // background holds no AO for a surface
        float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float planeDist = abs(orderedDot(nrm, q.xyz - p.xyz)) / tol;
        float depthWeight = exp(-0.5 * planeDist * planeDist);
        float normalWeight = 1.0;
        float w = bilinear * depthWeight * normalWeight;
        sum += w * ao;
        weightSum += w;
        float dz = abs(q.w - p.w);
        if (dz < fallbackDist) {
            fallbackDist = dz;
            fallback = ao;
        }
    }
    return weightSum > 1e-5 ? sum / weightSum : fallback;
}
