// What the SDF ambient-occlusion kernels share (the SDF AO reference (docs/kernels.md)):
// the G-buffer pixel taken back to world space, where the scene's distance
// function lives, and the distance function itself. These kernels read the
// G-buffer only to know where each pixel's surface is; the occlusion comes
// from the signed-distance scene, so they need --scene to be the scene the
// G-buffer shows (the ray-marched or the rasterised one), never an import.
//
// The seed's measure is "expected minus actual distance": at a point a
// height h above an open surface the scene distance is h, and whatever the
// scene reports below that is occluding geometry. Every kernel here gives
// exactly 1 on an open plane.
#include "include/common.glsl"
#include "include/noise.glsl"
#include "include/sdf_scenes.glsl"

struct SdfSurface {
    vec3 position;   // world space
    vec3 normal;     // world space, unit
    bool background;
};

// The inverse of gbuffer_sdf.glsl's world -> view mapping: view x, y, z are
// the components along right, up and -forward of the camera basis.
SdfSurface sdfSurface(ivec2 pixel) {
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nv = texelFetch(in_normal, pixel, 0).xyz;
    SdfSurface s;
    s.background = isBackground(p.w) || dot(nv, nv) == 0.0;
    vec3 eye, target;
    sceneCamera(P.scene, P.view, eye, target);
    vec3 forward = normalize(target - eye);
    vec3 right = normalize(cross(forward, vec3(0.0, 1.0, 0.0)));
    vec3 up = cross(right, forward);
    s.position = eye + right * p.x + up * p.y - forward * p.z;
    s.normal = s.background ? vec3(0.0, 1.0, 0.0) : normalize(right * nv.x + up * nv.y - forward * nv.z);
    return s;
}

// Each kernel of the family defines only its estimator; background pixels
// (no surface) are fully open and never reach it.
float sdfAmbientOcclusion(ivec2 pixel, SdfSurface s);

void cavity_main(ivec2 pixel) {
    SdfSurface s = sdfSurface(pixel);
    float ao = s.background ? 1.0 : sdfAmbientOcclusion(pixel, s);
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
}

float sceneMap(vec3 p) {
    return sceneDistance(P.scene, p).x;
}

// The per-pixel seed of the kernels that randomise per pixel: the hash of
// noise.glsl, as an integer, so sample i can hash (seed + i).
uint sdfPixelSeed(ivec2 pixel) {
    return pcgHash(uint(pixel.x) + uint(pixel.y) * 65521u);
}

// The unit vector at height z (cos of the polar angle) and azimuth
// (cos, sin) = cs, flipped into n's hemisphere; cosTheta = its dot with n.
vec3 hemisphereDirection(float z, vec2 cs, vec3 n, out float cosTheta) {
    float r = sqrt(max(0.0, 1.0 - z * z));
    vec3 dir = vec3(r * cs.x, r * cs.y, z);
    cosTheta = dot(dir, n);
    if (cosTheta < 0.0) {
        dir = -dir;
        cosTheta = -cosTheta;
    }
    return dir;
}

// Sample i's fraction along the kernel's reach: 0 for the first, 1 for the
// last, evenly between (0 when there is one sample).
float sdfSpread(int i, int n) {
    return n > 1 ? float(i) / float(n - 1) : 0.0;
}
