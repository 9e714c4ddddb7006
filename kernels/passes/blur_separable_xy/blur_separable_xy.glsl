// Both passes of the separable depth-aware blur (include/blur_separable.glsl)
// in one dispatch: the workgroup decodes its tile of keys, r texels wider on
// every side, into shared memory once; blurs each of its tile's rows along x
// (its own rows and the r above and below, which the vertical taps read);
// then blurs its pixels along y over those. The sums are the pair's, tap for
// tap, and the horizontal result is rounded to a half float as the pair's
// RGBA16F key between its passes rounds it. What it saves: one launch, and
// the key's store and reload between the passes; what it pays: the rows
// above and below are blurred along x by both workgroups that share them.
// Compute only, the radius compiled in; a tile that would not fit in 16 KiB
// of shared memory (r > 5 in 16x16 workgroups) takes the pair instead
// (harness/pipeline/pipelines.cpp, fusedBlurFits).
#include "include/common.glsl"
#include "include/octahedral.glsl"

#if !defined(CAVITY_STAGE_COMPUTE) || !defined(CAVITY_CONST_blur)
#error blur_separable_xy runs on the compute stage with its radius compiled in
#endif

const int R = CAVITY_CONST_blur;
const int kW = CAVITY_WORKGROUP_X + 2 * R, kH = CAVITY_WORKGROUP_Y + 2 * R;
shared vec4 tileNormalDepth[kW * kH];
shared float tileAo[kW * kH];
// The rows' horizontal results: CAVITY_WORKGROUP_X columns, kH rows.
shared float rowAo[CAVITY_WORKGROUP_X * kH];

float tapWeight(int t, vec3 N, vec3 tapNormal, float dd, float twoSigma2) {
    return P.weights[abs(t) >> 2][abs(t) & 3] * max(0.0, dot(N, tapNormal)) * exp(-dd * dd / twoSigma2);
}

// The blur along `stride` of the texel at tile index c, over the AO at
// index a, a + aStride, ... of the tile (`rows` false) or of the rows'
// results (`rows` true): blurAlong() of include/blur_separable.glsl, taps
// from -R to R, the sums in its order.
float blurAxis(int c, int stride, int a, int aStride, bool rows) {
    vec4 centre = tileNormalDepth[c];
    float ao = rows ? rowAo[a] : tileAo[a];
    if (R == 0 || isBackground(centre.w)) return ao;
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;
    float s = 0.0, total = 0.0;
    for (int t = -R; t <= R; ++t) {
        vec4 tap = tileNormalDepth[c + t * stride];
        float W = tapWeight(t, centre.xyz, tap.xyz, centre.w - tap.w, twoSigma2);
        W = isBackground(tap.w) ? 0.0 : W;
        s += (rows ? rowAo[a + t * aStride] : tileAo[a + t * aStride]) * W;
        total += W;
    }
    return s + (1.0 - total) * ao;
}

void cavity_main(ivec2 pixel) {
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * ivec2(CAVITY_WORKGROUP_X, CAVITY_WORKGROUP_Y) - ivec2(R);
    const int group = CAVITY_WORKGROUP_X * CAVITY_WORKGROUP_Y;
    for (int i = int(gl_LocalInvocationIndex); i < kW * kH; i += group) {
        ivec2 q = origin + ivec2(i % kW, i / kW);
        vec4 key = inImage(q) ? texelFetch(in_ao_key, q, 0) : vec4(0.0);
        tileNormalDepth[i] = vec4(octDecode(key.ba), key.g);
        tileAo[i] = key.r;
    }
    barrier();
    // Along x, every row of the tile at the workgroup's columns.
    for (int i = int(gl_LocalInvocationIndex); i < CAVITY_WORKGROUP_X * kH; i += group) {
        int c = (i / CAVITY_WORKGROUP_X) * kW + R + i % CAVITY_WORKGROUP_X;
        rowAo[i] = unpackHalf2x16(packHalf2x16(vec2(blurAxis(c, 1, c, 1, false), 0.0))).x;
    }
    barrier();
    if (!inImage(pixel)) return;
    // Along y over the rows' results.
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    int c = (local.y + R) * kW + local.x + R;
    int row = (local.y + R) * CAVITY_WORKGROUP_X + local.x;
    write_ao(pixel, vec4(blurAxis(c, kW, row, CAVITY_WORKGROUP_X, true), 0.0, 0.0, 0.0));
}
