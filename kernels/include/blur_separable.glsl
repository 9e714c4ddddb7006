// One axis of the separable depth-aware blur of the fast AO pipelines
// (blur_separable_x.glsl, then blur_separable_y.glsl). Each pass reads one
// RGBA16F texel per tap, AO, linear depth and the octahedral normal packed
// together (after Scalable Ambient Obscurance, which packs AO and depth):
// 2 (2r + 1) fetches in all, against the (2r + 1)^2 taps of three images each
// of blur_bilateral.glsl.
//
// Each tap is weighted as blur_bilateral.glsl weighs it: the 1-D Gaussian
// (the same weights, so r and sigma = r / 2 mean the same), times the normal
// agreement max(0, N . Ni), times exp(-dd^2 / (2 sigma_d^2)) in depth; the
// weight rejected goes back to the centre, so nothing crosses a silhouette
// or a crease. An earlier key of AO and depth alone (32 bits, no normal)
// blurred the slats' creases together: 0.122 MAE against the truth where the
// 2-D blur gives 0.091 (lavapipe, 640x360). What the two passes still cannot
// do: a diagonal tap is weighed by way of the pixel the first pass met, not
// against the centre directly.
#include "include/common.glsl"
#include "include/octahedral.glsl"

float gaussianWeight(int i) {
    return P.weights[i >> 2][i & 3];
}

// What the kernel blurs beside the key's AO, with the same weights, at
// texel q: the SSDO radiance (blur_separable_ssdo_x.glsl), or vec3(0.0)
// where there is nothing (the compiler drops it). Each kernel defines it.
vec3 blurredWith(ivec2 q);

// The centre's key with its AO blurred along `axis`, and in `value` what
// blurredWith() reads, blurred alike.
vec4 blurAlong(ivec2 pixel, ivec2 axis, out vec3 value) {
    vec4 centre = texelFetch(in_ao_key, pixel, 0);
    value = blurredWith(pixel);
    int r = P.blur;
    if (r == 0 || isBackground(centre.g)) return centre;
    vec3 N = octDecode(centre.ba);
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;
    float sum = 0.0;
    vec3 valueSum = vec3(0.0);
    float totalWeight = 0.0;
    for (int t = -r; t <= r; ++t) {
        ivec2 q = pixel + axis * t;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frame.size))) continue;
        vec4 tap = texelFetch(in_ao_key, q, 0);
        if (isBackground(tap.g)) continue;
        float dd = centre.g - tap.g;
        float W = gaussianWeight(abs(t)) * max(0.0, dot(N, octDecode(tap.ba))) * exp(-dd * dd / twoSigma2);
        sum += tap.r * W;
        valueSum += blurredWith(q) * W;
        totalWeight += W;
    }
    value = valueSum + (1.0 - totalWeight) * value;
    return vec4(sum + (1.0 - totalWeight) * centre.r, centre.gba);
}
