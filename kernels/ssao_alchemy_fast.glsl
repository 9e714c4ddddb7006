// Alchemy ambient obscurance on the linear-depth pyramid: the estimator of
// ssao_alchemy.glsl (McGuire et al., HPG 2011) sample for sample, the same
// spiral, falloff, bias and contrast, but each sample's position is rebuilt
// from one 32-bit depth (depth_pyramid.glsl) instead of read as an RGBA32F
// texel: a quarter of the bytes, and for samples far from the pixel a
// coarser level, whose texels neighbouring pixels share in cache.
//
// The level grows with the sample's distance h from the pixel in pixels, as
// in Scalable Ambient Obscurance: level floor(log2 h) - 3, so samples within
// 16 px read level 0 and each doubling of h moves one level down. A texel of
// level l holds the depth of one real pixel up to 2^l pixels from the
// sample's, and the position is rebuilt on that pixel's ray, found by
// undoing the pyramid's picks: the sample is a true surface point, moved by
// under 2^l px in a disc of h >= 2^(l+3) px. Rebuilt on the sample's own ray
// instead, the borrowed depth puts a point off the surface by the depth
// change across 2^l px, which on a wall seen at a grazing angle is far over
// the bias: streaks of missing and false occlusion showed there.
//
// A second output packs AO with the pixel's linear depth and its normal
// (octahedral) in one RGBA16F texel, all the separable blur reads per tap.
#include "include/common.glsl"
#include "include/noise.glsl"
#include "include/octahedral.glsl"
#include "include/alchemy_spiral.glsl"
#include "include/pyramid.glsl"

// Sample i of the seed's spiral (include/alchemy_spiral.glsl), its
// direction read from P.spiral and turned by the pixel's phase: (cos, sin)
// of the phase once per pixel instead of once per sample.
ivec2 spiralSampleTurned(int i, vec2 phase, float discScale, vec2 fragCentre, out float h) {
    vec2 d = P.spiral[i].xy;
    EXACT vec2 dirCS = vec2(d.x * phase.x - d.y * phase.y, d.x * phase.y + d.y * phase.x);
    EXACT float radius = (float(i) + 0.5) * discScale;
    EXACT vec2 samplePos = fragCentre + dirCS * radius;
    h = radius;
    return ivec2(floor(samplePos));
}

// The sample count compiled in (KernelDecl::compileTime), up to 64, and the
// loop over the samples unrolled where the compiler takes the hint: the
// spiral's directions then come from fixed offsets of the uniform block.
// On the H200 that took 9% off the AO pass on Vulkan and nothing on GL,
// which keeps the loop rolled (bench/results/2026-12-03_h200_unroll).
#if defined(CAVITY_CONST_samples) && CAVITY_CONST_samples <= 64
#define SAMPLE_COUNT CAVITY_CONST_samples
#define CAVITY_SAMPLE_LOOP CAVITY_UNROLL
#else
#define SAMPLE_COUNT P.samples
#define CAVITY_SAMPLE_LOOP
#endif

// The seed's sum S over the n samples around the pixel at X (normal N,
// depth d). `belowTiny`: every level a sample may read is below the tiny
// ones (pyramidTinyLevel), so no sample needs the other path; the caller
// passes a constant, and the compiler makes one copy of the loop for each.
float obscurance(const bool belowTiny, int n, ivec2 pixel, vec3 X, vec3 N, float d, int maxLevel, int tiny) {
    float R = P.radius;
    float c = 0.1 * R;
    float weight = 2.0 * PI * c / float(n);
    float discScale = spiralDiscScale(R, n, d);
    vec2 phase = cosSinTurns(samplePhase(pixel));
    vec2 fragCentre = vec2(pixel) + 0.5;

    // One sample at a time: fetching a batch of samples' depths before using
    // any was 20% slower on the H200 (bench/results/2026-12-03_h200_batched),
    // the registers it takes costing more occupancy than the latency it hides.
    float S = 0.0;
    CAVITY_SAMPLE_LOOP for (int i = 0; i < n; ++i) {
        float h;
        ivec2 s = spiralSampleTurned(i, phase, discScale, fragCentre, h);
        // One unsigned test for both sides: a negative coordinate wraps past any size.
        if (any(greaterThanEqual(uvec2(s), uvec2(frame.size)))) continue;
        // h < 2^31 here: the sample is inside the image.
        int level = pyramidLevel(int(h), maxLevel);
        // pyramidTexel, written out as in the variant measured fastest on the
        // H200; through a pyramidTexel whose tiny path was also different it
        // measured 2% slower, and which of the two cost that was not
        // separated (bench/results/2026-12-03_h200_overheads).
        ivec2 source;
        ivec2 t;
        if (belowTiny || level < tiny) {
            t = min(s >> level, (frame.size >> level) - 1);
            source = sourcePixelBelowTiny(t, level);
        } else {
            t = min(s >> level, levelSize(level) - 1);
            source = sourcePixel(t, level);
        }
        float zs = pyramidDepth(t, level);
        if (isBackground(zs)) continue;

        EXACT vec3 omega = positionAt(source, zs) - X;
        float omega2 = lengthSquared(omega);
        if (omega2 > R * R) continue;
        S += weight * max(0.0, dot(N, omega) - P.bias) / max(c * c, omega2);
    }
    return S;
}

void cavity_main(ivec2 pixel) {
    float d = pyramidDepth(pixel, 0);
    if (isBackground(d)) {
        write_ao(pixel, vec4(1.0));
        write_ao_key(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    vec3 X = positionAt(pixel, d);
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    int maxLevel = textureQueryLevels(in_zmip) - 1;
    int tiny = pyramidTinyLevel();
    // Any image of at least 2^maxLevel px a side reads only levels below
    // the tiny ones; that copy of the loop tests nothing more per sample.
    float S = maxLevel < tiny ? obscurance(true, SAMPLE_COUNT, pixel, X, N, d, maxLevel, tiny)
                              : obscurance(false, SAMPLE_COUNT, pixel, X, N, d, maxLevel, tiny);
    float A = pow(max(0.0, 1.0 - P.scale * S), P.contrast);
    write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));
    write_ao_key(pixel, vec4(A, d, octEncode(N)));
}
