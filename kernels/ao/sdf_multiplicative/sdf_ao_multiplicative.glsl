// Multiplicative SDF AO (the SDF AO reference (docs/kernels.md), variant 1): start at 1
// and multiply down by 1 - k (h - map) / h at each of n evenly spaced
// heights up to the reach R. Each factor is raised to 6/n, so the product
// is the seed's six-step product (R = 0.6, k = 0.2) at n = 6 and tends to
// the same value as n grows rather than to zero.
#include "include/sdf_ao.glsl"

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    int n = P.samples;
    float ao = 1.0;
    float exponent = 6.0 / float(n);
    for (int i = 0; i < n; ++i) {
        float h = P.radius * float(i + 1) / float(n);
        float d = sceneMap(s.position + s.normal * h);
        float factor = clamp(1.0 - P.strength * max(0.0, h - d) / h, 0.0, 1.0);
        ao *= pow(factor, exponent);
    }
    return ao;
}
