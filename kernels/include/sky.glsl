// The sky panorama the SSDO kernels light with (seed Ritschel et al., I3D 2009):
// a latitude-longitude image made on the CPU (const:sky, decl_screen_space.cpp)
// with its full mip chain, sampled with textureLod.
//
// Directions are view-space directions: the G-buffer holds view space and the
// frame carries no camera rotation, so the sky is attached to a level camera
// (view +Y is the zenith). Swapping in a world-space sky needs only a
// rotation applied to `d` here.
#include "include/screen_space.glsl"

// atan2(y, x) from +, -, * and portableReciprocal only, the same bits as
// the CPU reference: GLSL's atan may be thousands of ulp off (and is, on
// llvmpipe, enough to move a sample across a quarter of a level-4 texel
// next to the sun). Octant reduction to a = min/max in [0, 1], then an odd
// polynomial for atan(a) (error about 1e-5 rad: it only has to be the same
// on both sides, and close enough to put the sun where the panorama has it).
float portableAtan2(float y, float x) {
    float ax = abs(x), ay = abs(y);
    float hi = max(ax, ay), lo = min(ax, ay);
    if (hi == 0.0) return 0.0;
    EXACT float a = lo * portableReciprocal(hi);
    EXACT float a2 = a * a;
    EXACT float r = a * (0.99997726 + a2 * (-0.33262347 + a2 * (0.19354346 + a2 * (-0.11643287 + a2 * (0.05265332 + a2 * -0.01172120)))));
    if (ay > ax) r = 1.5707964 - r;
    if (x < 0.0) r = 3.1415927 - r;
    return y < 0.0 ? -r : r;
}

// u = 0.5 is +Z, the direction behind the camera, so the u seam (where a
// clamp-to-edge sampler cannot blend across) sits straight ahead, -Z: the
// hemispheres of surfaces the camera can see point away from it and almost
// never reach there. v = 0 is the zenith (row 0, the top); v is
// acos(y) / pi, written as atan2(sqrt(1 - y^2), y).
vec2 skyUv(vec3 d) {
    EXACT float u = portableAtan2(d.x, d.z) * 0.15915494 + 0.5;
    EXACT float s2 = max(1.0 - d.y * d.y, 0.0);
    EXACT float s = s2 > 0.0 ? s2 * portableInverseSqrt(s2) : 0.0;
    EXACT float v = portableAtan2(s, d.y) * 0.31830987;
    return vec2(u, v);
}

// Rec. 709 luminance: the weight seed 003 gives each direction's radiance
// in the visibility fraction.
float skyLuminance(vec3 c) {
    return orderedDot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Irradiance / pi of the whole panorama for a surface of normal n, from its
// 9 spherical-harmonic coefficients (Ramamoorthi & Hanrahan 2001): the "SH
// diffuse" term seed 003's visibility mode scales. sh[k].rgb already holds
// the band's convolution factor A_l / pi and the basis constant, so this is
// a plain dot with the polynomial basis.
vec3 skyAmbient(vec4 sh[9], vec3 n) {
    vec3 e = sh[0].rgb;
    e += sh[1].rgb * n.y;
    e += sh[2].rgb * n.z;
    e += sh[3].rgb * n.x;
    e += sh[4].rgb * (n.x * n.y);
    e += sh[5].rgb * (n.y * n.z);
    e += sh[6].rgb * (3.0 * n.z * n.z - 1.0);
    e += sh[7].rgb * (n.x * n.z);
    e += sh[8].rgb * (n.x * n.x - n.y * n.y);
    return max(e, vec3(0.0));
}
