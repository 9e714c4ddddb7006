// Ground-truth ambient occlusion for the quality measurements: the
// cosine-weighted fraction of the normal's hemisphere from which a ray
// escapes the signed-distance scene within the radius R, estimated with
// `rays` rays (1024 or more) sphere-traced against the scene itself
// (the SDF AO reference (docs/kernels.md)'s map). With cosine-weighted directions the
// estimator is the plain fraction of rays that escape. Directions form a
// Fibonacci lattice on the unit square (u = (i + 0.5) / N, v = i / phi),
// mapped to the hemisphere by r = sqrt(u), and rotated in azimuth by the
// pixel's hash: stratified, so 1024 rays leave an error near 1/1024 rather
// than the 1/32 of independent random rays. Slow by design: run it at low
// resolution.
#include "include/sdf_ao.glsl"

// A probe ray starts this far above the surface, clear of the G-buffer's
// own hit tolerance, and counts a hit within this distance of a surface.
const float GT_OFFSET = 2e-3;
const float GT_HIT = 2e-4;
const int GT_MAX_STEPS = 128;

// An orthonormal basis around n without a branch on n's direction
// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
void basisAround(vec3 n, out vec3 t, out vec3 b) {
    float sgn = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + sgn * n.x * n.x * a, sgn * c, -sgn * n.x);
    b = vec3(c, sgn + n.y * n.y * a, -n.y);
}

// True when the ray from o along dir meets the scene within `reach`. A ray
// still creeping along a surface after GT_MAX_STEPS counts as blocked.
bool blocked(vec3 o, vec3 dir, float reach) {
    float t = 0.0;
    for (int i = 0; i < GT_MAX_STEPS; ++i) {
        float d = sceneMap(o + dir * t);
        if (d < GT_HIT) return true;
        t += d;
        if (t >= reach) return false;
    }
    return true;
}

float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s) {
    vec3 t, b;
    basisAround(s.normal, t, b);
    vec3 origin = s.position + s.normal * GT_OFFSET;
    float rotation = pixelHash(pixel);
    int n = P.rays;
    int open = 0;
    for (int i = 0; i < n; ++i) {
        float u = (float(i) + 0.5) / float(n);
        EXACT float turns = float(i) * 0.618034 + rotation;   // unfused, as on the CPU
        vec2 cs = cosSinTurns(turns);
        float r = sqrt(u);
        vec3 dir = t * (r * cs.x) + b * (r * cs.y) + s.normal * sqrt(max(0.0, 1.0 - u));
        if (!blocked(origin, dir, P.radius)) ++open;
    }
    return float(open) / float(n);
}
