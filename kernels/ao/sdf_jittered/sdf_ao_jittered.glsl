// Jittered SDF AO (the SDF AO reference (docs/kernels.md), variant 3): n probes along
// the normal at heights l = (i + j) R / n, i = 1..n, each jittered by j in
// [0, 1) so that fixed spacing does not band; the shortfall l - map is
// weighted 1 / (1 + l), AO = 1 - k * mean, clamped. The seed's jitter is a
// hash of i alone, the same in every pixel, which moves the bands rather
// than breaking them up; here j is the pixel's hash rotated by the golden
// ratio per probe, different in every pixel and evenly spread over the n
// probes, so the blur averages it away. R = 2 is the seed's maxDist 4.
#include "include/sdf_ao.glsl"

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    int n = P.samples;
    float u = pixelHash(pixel);
    float occ = 0.0;
    for (int i = 1; i <= n; ++i) {
        // precise: no fused multiply-add, so the CPU gets the same j
        // (fract() would turn an ulp at a wrap into a whole probe step).
        EXACT float turn = u + float(i) * 0.618034;
        float j = fract(turn);
        float l = (float(i) + j) * P.radius / float(n);
        occ += (l - sceneMap(s.position + s.normal * l)) / (1.0 + l);
    }
    return clamp(1.0 - P.strength * occ / float(n), 0.0, 1.0);
}
