// Classic SDF ambient occlusion (the SDF AO reference (docs/kernels.md), step 3): probe
// the distance field at n heights h along the normal, from 0.01 to the
// reach R, and add up the shortfall h - map(p + h N), nearer probes
// weighted more (0.95 per fifth of the reach); AO = 1 - k * sum, clamped.
// The sum is scaled by 5/n so that the answer does not depend on n beyond
// the sampling: at n = 5, R = 0.13, k = 3 this is the seed's five-tap AO.
#include "include/sdf_ao.glsl"

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    int n = P.samples;
    float occ = 0.0;
    for (int i = 0; i < n; ++i) {
        float t = sdfSpread(i, n);
        float h = 0.01 + (P.radius - 0.01) * t;
        float d = sceneMap(s.position + s.normal * h);
        occ += (h - d) * pow(0.95, 4.0 * t);
    }
    occ *= 5.0 / float(n);
    return clamp(1.0 - P.strength * occ, 0.0, 1.0);
}
