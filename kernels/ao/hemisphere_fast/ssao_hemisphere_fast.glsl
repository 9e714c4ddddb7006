// Hemisphere-kernel SSAO on the linear-depth pyramid: hemisphere_cosine's
// estimator (seed 004, the hemisphere SSAO lesson (docs/kernels.md), with its sampling fixed:
// n / steps cosine-weighted rays in the normal hemisphere, each walked in
// `steps` points out to R and blocked when any point is, AO = (1 - blocked
// rays / rays)^k, the range check) with one 8-byte fetch per point (a depth
// and its source pixel) instead of a position and a normal. The kernel points are hemisphere_cosine's
// (cosineKernel, decl_screen_space.cpp), made on the CPU.
//
// What differs from ssao_hemisphere.glsl, and why:
//  * The stored point q is rebuilt from the pyramid's linear depth on its
//    texel's own ray, and far points read a coarser level, as in
//    ssao_alchemy_fast.glsl.
//  * The occlusion test needs no normal at q. The seed decides "is the
//    sample behind the stored surface" with q's plane, because the sample s
//    projects up to half a texel beside q's ray, and on a plane seen at a
//    grazing angle the depth changes over that half texel by more than any
//    bias. Here both are measured along the receiver's normal N instead:
//    q occludes when it rises above the sample's level by more than `bias`,
//        N . q - N . s > bias,   with N . q = z_q (N . ray_q),
//    which is the depth test along q's ray against the point where that ray
//    crosses the plane through s parallel to the receiver's. On the
//    receiver's own plane q sits exactly at the receiver's level, under
//    every sample, at any angle: no self-shadowing without q's normal. Where
//    q's ray meets the receiver's plane from behind (N . ray_q >= 0, a
//    receiver seen edge-on), the plain depth test z_q + bias < z_s decides,
//    as the seed's does where q has no normal.
//  * That test alone misses a point that has passed under or through a thin
//    occluder seen from above (a slat seen from the front, a plate over a
//    gap): the point then rises as high as the occluder's top, or higher.
//    So a point behind the stored surface along its own ray is blocked as
//    well when that surface stands above the receiver's tangent plane by
//    more than `bias` (pyramidBlocks, include/pyramid.glsl), which the
//    receiver's own plane never does. It took the blurred error on slats
//    from 0.090 to 0.070 MAE (lavapipe, 640x360, n16; hemisphere_cosine
//    0.087) and left corner's at 0.020.
//  * The 4x4 noise tile and its box blur give way to a per-pixel rotation
//    (pixelHash, as alchemy_fast) and the separable blur of the packed key.
//  * A point that projects off the screen tests nothing (Alchemy's rule),
//    where the seed tests it against the border texel.
// The range check is seed 004's, smoothstep(0, 1, R / |dz|), evaluated only
// where it is under 1.
#include "include/screen_space.glsl"
#include "include/octahedral.glsl"
#include "include/pyramid.glsl"

// How much the kernel point k (tangent frame tn, b, N; scaled by
// lengthScale) is occluded: 0 or 1, or the range check's fade.
float occludedBy(PyramidView v, vec3 X, vec3 N, float level, float d, vec3 k, vec3 tn, vec3 b, float lengthScale,
                 ivec2 pixel) {
    EXACT vec3 s = X + (tn * k.x + b * k.y + N * k.z) * lengthScale;
    ivec2 source;
    float zq;
    if (!pyramidBlocks(v, N, level, s, pixel, P.bias, source, zq)) return 0.0;
    float dz = abs(d - zq);
    return (P.range_check != 0 && dz > P.radius) ? smoothstep(0.0, 1.0, P.radius / dz) : 1.0;
}

// The share of the pixel's rays that are blocked. With v.tiny a constant
// 32 (belowTiny) the compiler drops the tiny levels' path.
float blockedShare(PyramidView view, ivec2 pixel, vec3 X, vec3 N, float level, float d, vec3 tn, vec3 b) {
    // Points come in groups along one ray (P.kernel[i].w = 1 closes one):
    // a ray is blocked when any of its points is. Every point is fetched,
    // also after one has blocked its ray fully (max() then keeps 1):
    // skipping those was slower on the H200 (study
    // 2026-12-03_h200_batched). step_jitter moves ray g's
    // points in by a share u of a step, drawn per pixel and ray, as in
    // ssao_hemisphere.glsl.
    // The point count compiled in and the loop unrolled, as in
    // ssao_alchemy_fast.glsl, which made this pass faster on the H200's
    // Vulkan (study 2026-12-03_h200_unroll).
#ifdef CAVITY_REPEAT_samples   // a count from 1 to 64 compiled in (assemble())
    const int n = CAVITY_CONST_samples;
#define POINT_LOOP CAVITY_UNROLL
#else
#define POINT_LOOP
    int n = clamp(P.samples, 1, 256);
#endif
    float R = P.radius;
    float occlusion = 0.0, directions = 0.0, blocked = 0.0, u = 0.0;
#if defined(CAVITY_REPEAT_samples) && defined(CAVITY_REPEAT_steps)
    // The rays' shape compiled in as well (cosineKernel's: ray g is points
    // g steps .. g steps + steps - 1, the last ray shorter when steps does
    // not divide n, and one ray of every point when steps is over n), so
    // that each point's place on its ray, and with it the jitter's
    // 1 / (j + 1), is a constant, and the test that closes a ray is gone.
    // That made this pass faster on both APIs of the H200, with the same
    // images (study 2026-12-04_h200_hemisphere_rays). NVIDIA's GL driver
    // keeps a loop of constant count rolled; there two rays an iteration were
    // faster than one.
#if CAVITY_CONST_steps <= CAVITY_CONST_samples
#define RAY_STEPS CAVITY_CONST_steps
#define RAY_POINTS CAVITY_REPEAT_steps
#else
#define RAY_STEPS CAVITY_CONST_samples
#define RAY_POINTS CAVITY_REPEAT_samples
#endif
#define RAY_POINT(ray, j) { \
        EXACT float lengthScale = R; \
        if (P.step_jitter != 0) lengthScale = R * (1.0 - u * portableReciprocal(float((j) + 1))); \
        blocked = max(blocked, occludedBy(view, X, N, level, d, P.kernel[(ray) * RAY_STEPS + (j)].xyz, tn, b, lengthScale, pixel)); \
    }
#define RAY_POINT_OF_THIS_RAY(j) RAY_POINT(ray, j)
    // Ray g, its points the statement POINTS (of `ray`).
#define RAY(g, POINTS) { \
        int ray = g; \
        if (P.step_jitter != 0) u = sampleHash(phasePixel(pixel), ray); \
        blocked = 0.0; \
        POINTS \
        occlusion += blocked; \
        directions += 1.0; \
    }
#define WHOLE_RAY RAY_POINTS(RAY_POINT_OF_THIS_RAY)
    const int kRays = CAVITY_CONST_samples / RAY_STEPS;   // whole rays
#if !defined(VULKAN) && (CAVITY_CONST_samples / RAY_STEPS) % 2 == 0
    for (int g = 0; g < kRays; g += 2) {
        RAY(g, WHOLE_RAY)
        RAY(g + 1, WHOLE_RAY)
    }
#else
    POINT_LOOP for (int g = 0; g < kRays; ++g) RAY(g, WHOLE_RAY)
#endif
#if CAVITY_CONST_samples % RAY_STEPS != 0
    // The last ray, shorter.
#define SHORT_RAY POINT_LOOP for (int j = 0; j < CAVITY_CONST_samples % RAY_STEPS; ++j) RAY_POINT(ray, j)
    RAY(kRays, SHORT_RAY)
#endif
#else
    // Past 64 points: the rays' shape from the table, P.kernel[i].w = 1
    // closing one.
    int inGroup = 0;
    for (int i = 0; i < n; ++i) {
        vec4 k = P.kernel[i];
        if (inGroup == 0 && P.step_jitter != 0) u = sampleHash(phasePixel(pixel), int(directions));
        EXACT float lengthScale = R;
        if (P.step_jitter != 0) lengthScale = R * (1.0 - u * portableReciprocal(float(inGroup + 1)));
        blocked = max(blocked, occludedBy(view, X, N, level, d, k.xyz, tn, b, lengthScale, pixel));
        ++inGroup;
        if (k.w > 0.5 || i == n - 1) {
            occlusion += blocked;
            directions += 1.0;
            blocked = 0.0;
            inGroup = 0;
        }
    }
#endif
    return occlusion / directions;
}

void cavity_main(ivec2 pixel) {
    float d = pyramidDepth(pixel, 0);
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    if (isBackground(d) || lengthSquared(N) == 0.0) {
        write_ao(pixel, vec4(1.0));
        write_ao_key(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    N = portableNormalize(N);
    vec3 X = positionAt(pixel, d);
    PyramidView view = pyramidView();
    float level = orderedDot(N, X);

    // The kernel's tangent frame, turned about N by the pixel's phase.
    vec3 tn, b;
    tangentFrame(cosSinTurns(samplePhase(pixel)), N, tn, b);

    // Any image of at least 2^maxLevel px a side reads only levels below
    // the tiny ones: that copy of the loop is compiled without their path.
    float share = view.maxLevel < view.tiny ? blockedShare(belowTiny(view), pixel, X, N, level, d, tn, b)
                                            : blockedShare(view, pixel, X, N, level, d, tn, b);
    float ao = pow(max(1.0 - share, 0.0), P.contrast);
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
    write_ao_key(pixel, vec4(ao, d, octEncode(N)));
}
