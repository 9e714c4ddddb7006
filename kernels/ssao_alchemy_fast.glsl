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

    // One sample at a time: fetching a batch of samples' depths before using
    // any was 20% slower on the H200 (bench/results/2026-12-03_h200_batched),
    // the registers it takes costing more occupancy than the latency it hides.
    int n = P.samples;
    float R = P.radius;
    float c = 0.1 * R;
    float weight = 2.0 * PI * c / float(n);
    float discScale = spiralDiscScale(R, n, d);
    vec2 phase = cosSinTurns(samplePhase(pixel));
    vec2 fragCentre = vec2(pixel) + 0.5;
    int tiny = pyramidTinyLevel();

    float S = 0.0;
    for (int i = 0; i < n; ++i) {
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
        if (level < tiny) {
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
    float A = pow(max(0.0, 1.0 - P.scale * S), P.contrast);
    write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));
    write_ao_key(pixel, vec4(A, d, octEncode(N)));
}
