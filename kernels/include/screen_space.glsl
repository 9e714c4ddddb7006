// Helpers shared by the screen-space kernels (hemisphere SSAO, SSDO, the
// half-resolution pair): the maps between view space, the hardware depth
// value and texels, and the few exactly reproducible operations they need.
//
// Same discipline as common.glsl: whatever ends in a texel index or a
// threshold test is built from +, -, * in a fixed order, `precise` (no fma),
// with portableReciprocal instead of a division, so the CPU references
// (harness/reference/ref_hemisphere.cpp, ref_ssdo.cpp) land on the same
// texel. A one-ulp difference that moves one sample to the next texel
// changes AO by 1/n, far over the 1e-3 the tests allow.
#include "include/common.glsl"
#include "include/noise.glsl"

// a.b with the additions in a fixed order (dot() leaves the order open).
float orderedDot(vec3 a, vec3 b) {
    EXACT float r = a.x * b.x + a.y * b.y + a.z * b.z;
    return r;
}

// a x b, each component's products rounded before the difference (cross()
// is an extended instruction, which `precise` is not sure to reach).
vec3 orderedCross(vec3 a, vec3 b) {
    EXACT vec3 r = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
    return r;
}

// 1 / sqrt(x) for x > 0 with the same bits everywhere (GLSL's inversesqrt
// may be 2 ulp off): an exponent-bit estimate (relative error under 3.5e-2)
// and four Newton steps y' = y (1.5 - x/2 y^2), which converge to rounding.
float portableInverseSqrt(float x) {
#ifdef CAVITY_INEXACT
    return inversesqrt(x);
#else
    EXACT float h = 0.5 * x;
    EXACT float y = intBitsToFloat(0x5F375A86 - (floatBitsToInt(x) >> 1));
    y = y * (1.5 - h * y * y);
    y = y * (1.5 - h * y * y);
    y = y * (1.5 - h * y * y);
    y = y * (1.5 - h * y * y);
    return y;
#endif
}

vec3 portableNormalize(vec3 v) {
    EXACT vec3 r = v * portableInverseSqrt(lengthSquared(v));
    return r;
}

// frame matrix times (v, w) as explicit column sums: the order of the
// additions in a mat4 * vec4 is the implementation's.
// Gram-Schmidt (seed 004, step 4): the vector (r, 0) minus its component
// along the unit normal n is a tangent t, and b = n x t completes the frame.
// It vanishes only when n lies in the view xy plane along r; the
// perpendicular of r in xy is then a tangent instead.
void tangentFrame(vec2 r, vec3 n, out vec3 t, out vec3 b) {
    vec3 rv = vec3(r, 0.0);
    EXACT vec3 g = rv - n * orderedDot(rv, n);
    if (lengthSquared(g) < 1e-6) {
        rv = vec3(-r.y, r.x, 0.0);
        g = rv - n * orderedDot(rv, n);
    }
    t = portableNormalize(g);
    b = orderedCross(n, t);
}

vec4 mulPoint(mat4 m, vec3 v, float w) {
    EXACT vec4 r = m[0] * v.x + m[1] * v.y + m[2] * v.z + m[3] * w;
    return r;
}

// View position on the ray through the centre of `texel` at hardware depth
// `depth`, by the inverse projection (the hemisphere SSAO lesson (docs/kernels.md), "Reconstruct
// view-space position from depth"). Our projection (harness/camera.cpp)
// already sends +Y up to NDC y = -1 = row 0, so unlike the seed's
// D3D-style code there is no flip of y: row 0 maps straight to NDC y = -1.
vec3 viewFromDepth(ivec2 texel, float depth) {
    EXACT vec2 ndc = (vec2(texel) + 0.5) * frame.invSize * 2.0 - 1.0;
    EXACT vec4 v = mulPoint(frame.invProj, vec3(ndc, depth), 1.0);
    // v.w = -1 / z_view > 0 for every point in front of the camera.
    EXACT vec3 p = v.xyz * portableReciprocal(v.w);
    return p;
}

// The texel a view-space point projects into (frame.proj, then floor: the
// texel whose square holds it). False when the point is not in front of the
// camera. `texel` may lie outside the image; the caller decides whether
// that means "clamp" (hemisphere) or "open sky" (SSDO).
bool texelOfView(vec3 p, out ivec2 texel) {
    EXACT vec4 clip = mulPoint(frame.proj, p, 1.0);
    texel = ivec2(-1);
    if (clip.w <= 0.0) return false;
    // Clamped before the int conversion, which is undefined for huge values
    // (a point just in front of the camera plane).
    EXACT vec2 uv = clamp(clip.xy * portableReciprocal(clip.w) * 0.5 + 0.5, vec2(-1.0), vec2(2.0));
    EXACT vec2 t = floor(uv * vec2(frame.size));
    texel = ivec2(t);
    return true;
}

bool texelInside(ivec2 texel) {
    return all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, frame.size));
}

// A uniform number in [0, 1) per pixel and sample index, seeded by the pixel
// position only (noise.glsl's hashes, exact on the CPU too).
float sampleHash(ivec2 pixel, int i) {
    return hashToUnit(pcgHash(pcgHash(uint(pixel.x) + uint(pixel.y) * 65521u) + uint(i)));
}

// Where half texel `pixel`'s own centre ray meets the tangent plane of the
// full texel (position p, normal n) the half texel copied; false, leaving
// `hit` unset, where the plane faces away or is so near edge-on that the
// hit moves the depth by over a twentieth (then the copy's own point
// stands). frame is the half frame. The two half-resolution depths put the
// copied point back on the ray the kernels rebuild positions on: the
// hardware depth (depth_from_position_half.glsl) and the pyramid's linear
// depth (include/downsample.glsl).
bool halfTexelRayHit(ivec2 pixel, vec3 p, vec3 n, out vec3 hit) {
    EXACT vec2 ndc = (vec2(pixel) + 0.5) * frame.invSize * 2.0 - 1.0;
    EXACT vec3 ray = vec3(ndc.x * frame.camera.x, -ndc.y * frame.camera.y, -1.0);
    EXACT float facing = orderedDot(n, ray);
    if (lengthSquared(n) > 0.0 && facing < 0.0) {
        // ray.z = -1, so t is the linear depth of the hit.
        EXACT float t = orderedDot(n, p) * portableReciprocal(facing);
        EXACT float moved = abs(t + p.z);
        if (t > 0.0 && moved <= 0.05 * -p.z) {
            hit = ray * t;
            return true;
        }
    }
    return false;
}
