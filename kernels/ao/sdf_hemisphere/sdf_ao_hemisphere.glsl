// Random-hemisphere SDF AO (the SDF AO reference (docs/kernels.md), variant 4): n random
// directions, flipped into the normal's hemisphere, probed at heights
// h = 0.01 + R t^2 that crowd near the surface. The expected distance of a
// probe h along a direction at angle theta to the normal is h cos(theta)
// (its height over the tangent plane), so each probe scores
// 1 - k (h cos(theta) - map) / h, clamped to [0, 1], and AO is the mean.
// (The seed scores clamp(5 map / h) against 1, which gives 0.9 rather than
// 1 on an open plane: a probe at a grazing angle is near the plane though
// nothing occludes it.) Directions are uniform on the sphere from a hash of
// (pixel, i), through the portable sin/cos, so the CPU gets them too.
#include "include/sdf_ao.glsl"

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    int n = P.samples;
    uint seed = sdfPixelSeed(pixel);
    float vis = 0.0;
    for (int i = 0; i < n; ++i) {
        uint h1 = pcgHash(seed + uint(i));
        float z = 1.0 - 2.0 * hashToUnit(h1);
        vec2 cs = cosSinTurns(hashToUnit(pcgHash(h1)));
        float c;
        vec3 dir = hemisphereDirection(z, cs, s.normal, c);
        float t = sdfSpread(i, n);
        float h = 0.01 + P.radius * t * t;
        float d = sceneMap(s.position + dir * h);
        vis += clamp(1.0 - P.strength * (h * c - d) / h, 0.0, 1.0);
    }
    return vis / float(n);
}
