// Fibonacci-hemisphere SDF AO (the SDF AO reference (docs/kernels.md), variant 5): the
// n points of a Fibonacci sphere (azimuth i / phi turns, z evenly spaced)
// are a near-uniform set of directions with none of random sampling's
// clumps; each is flipped into the normal's hemisphere and probed at a
// random distance s in [0.1 R, R] from a point 0.01 above the surface. As
// in the hemisphere variant the probe's expected distance is its height
// over the tangent plane, 0.01 + s cos(theta), and it scores
// 1 - k (expected - map) / (0.01 + s), clamped; AO is the mean. The seed's
// random distance is a hash of i alone; here it is a hash of (pixel, i).
#include "include/sdf_ao.glsl"

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    int n = P.samples;
    uint seed = sdfPixelSeed(pixel);
    vec3 origin = s.position + s.normal * 0.01;
    float vis = 0.0;
    for (int i = 0; i < n; ++i) {
        float z = 1.0 - (2.0 * float(i) + 1.0) / float(n);
        vec2 cs = cosSinTurns(float(i) * 0.618034);
        float c;
        vec3 dir = hemisphereDirection(z, cs, s.normal, c);
        float dist = P.radius * (0.1 + 0.9 * hashToUnit(pcgHash(seed + uint(i))));
        float d = sceneMap(origin + dir * dist);
        vis += clamp(1.0 - P.strength * (0.01 + dist * c - d) / (0.01 + dist), 0.0, 1.0);
    }
    return vis / float(n);
}
