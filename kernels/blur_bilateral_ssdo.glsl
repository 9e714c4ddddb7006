// The bilateral blur of blur_bilateral.glsl (000_79d41de70034b569.txt),
// applied to both SSDO outputs in one pass, as 003_9aa4a2c3c5c6ee23.txt
// extends its SSAO blur to the two MRT targets: visibility and radiance
// share every weight, so one loop over the taps serves both and the two stay
// aligned at every edge. Weights, parameters and edge rules (the weight the
// depth and normal terms reject stays with the centre) are those of
// blur_bilateral.glsl; see there for why each is so.
#include "include/common.glsl"

// P.weights: the 1-D Gaussian w[0..r] (blur_weights.cpp), normalised over
// the full symmetric kernel.
float gaussianWeight(int i) {
    return P.weights[i >> 2][i & 3];
}

void cavity_main(ivec2 pixel) {
    float centreVis = texelFetch(in_visibility, pixel, 0).r;
    vec3 centreRad = texelFetch(in_radiance, pixel, 0).rgb;
    float d = texelFetch(in_position, pixel, 0).w;
    int r = P.blur;
    if (r == 0 || isBackground(d)) {
        write_visibility(pixel, vec4(centreVis, 0.0, 0.0, 0.0));
        write_radiance(pixel, vec4(centreRad, 1.0));
        return;
    }
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;

    float visSum = 0.0;
    vec3 radSum = vec3(0.0);
    float totalWeight = 0.0;
    for (int y = -r; y <= r; ++y) {
        for (int x = -r; x <= r; ++x) {
            ivec2 q = pixel + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frame.size))) continue;
            float di = texelFetch(in_position, q, 0).w;
            if (isBackground(di)) continue;
            vec3 Ni = texelFetch(in_normal, q, 0).xyz;
            float spatial = gaussianWeight(abs(x)) * gaussianWeight(abs(y));
            float normalWeight = max(0.0, dot(N, Ni));
            float depthWeight = exp(-(d - di) * (d - di) / twoSigma2);
            float W = spatial * normalWeight * depthWeight;
            visSum += texelFetch(in_visibility, q, 0).r * W;
            radSum += texelFetch(in_radiance, q, 0).rgb * W;
            totalWeight += W;
        }
    }
    // As blur_bilateral.glsl: the spatial kernel sums to one, and whatever
    // weight the depth and normal terms reject stays with the centre tap.
    float kept = 1.0 - totalWeight;
    write_visibility(pixel, vec4(visSum + kept * centreVis, 0.0, 0.0, 0.0));
    write_radiance(pixel, vec4(radSum + kept * centreRad, 1.0));
}
