// One axis of the separable depth-aware blur of the fast AO pipelines
// (blur_separable_x.glsl, then blur_separable_y.glsl). Each pass reads one
// RG16F texel per tap, AO and linear depth packed together as Scalable
// Ambient Obscurance packs them: 2 (2r + 1) fetches of 32 bits in all,
// against the (2r + 1)^2 taps of three images each of blur_bilateral.glsl.
//
// Each tap is weighted by the 1-D Gaussian (the same weights as the 2-D
// blur's, so r and sigma = r / 2 mean the same) times the depth weight
// exp(-dd^2 / (2 sigma_d^2)) against the centre; the weight rejected goes
// back to the centre, as in blur_bilateral.glsl, so nothing crosses a
// silhouette. What the two passes cannot do that the 2-D blur does: weigh
// by normals (no room in 32 bits), so across a crease whose depth is
// continuous AO of the two faces mixes, and a diagonal tap is weighted by
// way of the pixel the first pass met, not against the centre directly.
// cavity quality measures both against the ground truth.
#include "include/common.glsl"

float gaussianWeight(int i) {
    return P.weights[i >> 2][i & 3];
}

// (blurred AO, centre depth) along `axis`.
vec2 blurAlong(ivec2 pixel, ivec2 axis) {
    vec2 centre = texelFetch(in_ao_key, pixel, 0).rg;
    int r = P.blur;
    if (r == 0 || isBackground(centre.g)) return centre;
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;
    float sum = 0.0;
    float totalWeight = 0.0;
    for (int t = -r; t <= r; ++t) {
        ivec2 q = pixel + axis * t;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frame.size))) continue;
        vec2 tap = texelFetch(in_ao_key, q, 0).rg;
        if (isBackground(tap.g)) continue;
        float dd = centre.g - tap.g;
        float W = gaussianWeight(abs(t)) * exp(-dd * dd / twoSigma2);
        sum += tap.r * W;
        totalWeight += W;
    }
    return vec2(sum + (1.0 - totalWeight) * centre.r, centre.g);
}
