// Multi-scale SDF AO (the SDF AO reference (docs/kernels.md), variant 2): heights double
// from R/64 to R (the seed's 0.1 .. 6.4 at n = 7), each factor the
// fraction map / h of the open-space distance, clamped to [0, 1]; short
// heights catch contact shadows, long ones the room. Factors are raised to
// 7/n (the seed's product at n = 7), and the result is compressed as the
// seed does: max(0.035, ao^0.3).
#include "include/sdf_ao.glsl"

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    int n = P.samples;
    float ao = 1.0;
    float exponent = 7.0 / float(n);
    for (int i = 0; i < n; ++i) {
        float h = P.radius * exp2(-6.0 * (1.0 - sdfSpread(i, n)));
        float d = sceneMap(s.position + s.normal * h);
        ao *= pow(clamp(d / h, 0.0, 1.0), exponent);
    }
    return max(0.035, pow(ao, 0.3));
}
