// Alchemy ambient obscurance on the linear-depth pyramid: the estimator of
// ssao_alchemy.glsl (McGuire et al., HPG 2011) sample for sample, the same
// spiral, falloff, bias and contrast, but each sample's position is rebuilt
// from one pyramid texel (depth_pyramid.glsl: a depth and the pixel it came
// from) instead of read as an RGBA32F texel: half the bytes, and for
// samples far from the pixel a coarser level, whose texels neighbouring
// pixels share in cache.
//
// The level grows with the sample's distance h from the pixel in pixels, as
// in Scalable Ambient Obscurance: level floor(log2 h) - 3, so samples within
// 16 px read level 0 and each doubling of h moves one level down. A texel of
// level l holds the depth of one real pixel up to 2^l pixels from the
// sample's, and the position is rebuilt on that pixel's ray, which the
// texel stores beside the depth: the sample is a true surface point, moved by
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
// positionAt() in fused multiply-adds (include/pyramid.glsl).
#define CAVITY_FMA_POSITIONS 1
#include "include/pyramid.glsl"

// With the GPU's own arithmetic the sum's common factor, the seed's
// 2 pi c / n, multiplies the sum once instead of every term (one multiply a
// sample); exact, it stays in each term as the CPU reference has it.
#ifdef CAVITY_INEXACT
#define WEIGHTED_TERM(weight, term) (term)
#define WEIGHTED_SUM(weight, sum) ((weight) * (sum))
#else
#define WEIGHTED_TERM(weight, term) ((weight) * (term))
#define WEIGHTED_SUM(weight, sum) (sum)
#endif

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
// samples unrolled: the spiral's directions then come from fixed offsets of
// the uniform block. Vulkan: the loop with the Unroll hint, which NVIDIA's
// driver takes (the AO pass faster on the H200). GL: the samples written
// out by the preprocessor (CAVITY_REPEAT_samples), because NVIDIA's GL
// driver keeps a loop rolled whatever the hint; written out, its AO pass
// was faster. Each API keeps the form measured faster on it: the GL form,
// with its per-sample function, made Vulkan's pass slower, and so did
// samples written out in the loop's own form (study 2026-12-03_h200_unroll).
#ifdef CAVITY_REPEAT_samples   // a count from 1 to 64 compiled in (assemble())
#define SAMPLE_COUNT CAVITY_CONST_samples
#define CAVITY_SAMPLE_LOOP CAVITY_UNROLL
#if !defined(VULKAN)
#define WRITE_SAMPLES_OUT 1
#endif
#else
#define SAMPLE_COUNT P.samples
#define CAVITY_SAMPLE_LOOP
#endif

#ifdef WRITE_SAMPLES_OUT
// What the pixel's inputs and the pass's constants are, for sampleTerm.
struct Receiver {
    vec3 X, N;           // its view position and normal
    vec2 phase;          // (cos, sin) of its sample phase
    vec2 fragCentre;
    float discScale;
    float R, c, weight;  // the radius, the seed's epsilon-like c, 2 pi c / n
    int maxLevel, tiny;
};

// Sample i's term of the seed's sum S, false where it adds nothing (off the
// image, on the background, beyond R). `belowTiny`: every level a sample may
// read is below the tiny ones (pyramidTinyLevel), so no sample needs the
// other path; the caller passes a constant, and the compiler makes one copy
// of the samples for each.
bool sampleTerm(const bool belowTiny, int i, Receiver r, out float term) {
    term = 0.0;
    float h;
    ivec2 s = spiralSampleTurned(i, r.phase, r.discScale, r.fragCentre, h);
    // One unsigned test for both sides: a negative coordinate wraps past any size.
    if (any(greaterThanEqual(uvec2(s), uvec2(frame.size)))) return false;
    // h < 2^31 here: the sample is inside the image.
    int level = pyramidLevel(int(h), r.maxLevel);
    ivec2 source;
    float zs = pyramidFetch(pyramidTexel(s, level, belowTiny ? 32 : r.tiny), level, source);
    if (isBackground(zs)) return false;

    EXACT vec3 omega = positionAt(source, zs) - r.X;
    float omega2 = lengthSquared(omega);
    if (omega2 > r.R * r.R) return false;
    term = WEIGHTED_TERM(r.weight, max(0.0, dot(r.N, omega) - P.bias) / max(r.c * r.c, omega2));
    return true;
}

// The seed's sum S over the receiver's samples, written out.
// One sample at a time: fetching a batch of samples' depths before using
// any was slower on the H200 (study 2026-12-03_h200_batched),
// the registers it takes costing more occupancy than the latency it hides.
float obscuranceWrittenOut(const bool belowTiny, Receiver r) {
    float S = 0.0, term;
#define SAMPLE_TERM(i) if (sampleTerm(belowTiny, i, r, term)) S += term;
    CAVITY_REPEAT_samples(SAMPLE_TERM)
    return WEIGHTED_SUM(r.weight, S);
}

// The receiver of the pixel at X (normal N, depth d) with n samples: the
// values obscurance() computes first, in the same operations.
Receiver receiverOf(ivec2 pixel, vec3 X, vec3 N, float d, int n, int maxLevel, int tiny) {
    Receiver r;
    r.X = X;
    r.N = N;
    r.R = P.radius;
    r.c = 0.1 * r.R;
    r.weight = 2.0 * PI * r.c / float(n);
    r.discScale = spiralDiscScale(r.R, n, d);
    r.phase = cosSinTurns(samplePhase(pixel));
    r.fragCentre = vec2(pixel) + 0.5;
    r.maxLevel = maxLevel;
    r.tiny = tiny;
    return r;
}
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
    // any was slower on the H200 (study 2026-12-03_h200_batched),
    // the registers it takes costing more occupancy than the latency it hides.
    float S = 0.0;
    CAVITY_SAMPLE_LOOP for (int i = 0; i < n; ++i) {
        float h;
        ivec2 s = spiralSampleTurned(i, phase, discScale, fragCentre, h);
        // One unsigned test for both sides: a negative coordinate wraps past any size.
        if (any(greaterThanEqual(uvec2(s), uvec2(frame.size)))) continue;
        // h < 2^31 here: the sample is inside the image.
        int level = pyramidLevel(int(h), maxLevel);
        ivec2 source;
        float zs = pyramidFetch(pyramidTexel(s, level, belowTiny ? 32 : tiny), level, source);
        if (isBackground(zs)) continue;

        EXACT vec3 omega = positionAt(source, zs) - X;
        float omega2 = lengthSquared(omega);
        if (omega2 > R * R) continue;
        S += WEIGHTED_TERM(weight, max(0.0, dot(N, omega) - P.bias) / max(c * c, omega2));
    }
    return WEIGHTED_SUM(weight, S);
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
#ifdef WRITE_SAMPLES_OUT
    Receiver r = receiverOf(pixel, X, N, d, SAMPLE_COUNT, maxLevel, tiny);
    float S = maxLevel < tiny ? obscuranceWrittenOut(true, r) : obscuranceWrittenOut(false, r);
#else
    float S = maxLevel < tiny ? obscurance(true, SAMPLE_COUNT, pixel, X, N, d, maxLevel, tiny)
                              : obscurance(false, SAMPLE_COUNT, pixel, X, N, d, maxLevel, tiny);
#endif
    float A = pow(max(0.0, 1.0 - P.scale * S), P.contrast);
    write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));
    write_ao_key(pixel, vec4(A, d, octEncode(N)));
}
