// Depth- and normal-aware (bilateral) blur of the raw AO
// (000_79d41de70034b569.txt). Each tap of a (2r+1)^2 Gaussian is further
// weighted by how much its surface agrees with the centre's: normals more
// than 90 degrees apart get nothing, and the weight falls off as a Gaussian
// in linear-depth difference. Smooths the spiral noise inside a surface
// without carrying darkness across a silhouette or a crease.
#include "include/common.glsl"

// P.weights holds the 1-D Gaussian w[0..r] (blur_weights.cpp), already
// normalised over the full symmetric kernel.
float gaussianWeight(int i) {
    return P.weights[i >> 2][i & 3];
}

void cavity_main(ivec2 pixel) {
    float centreAo = texelFetch(in_ao, pixel, 0).r;
    float d = texelFetch(in_position, pixel, 0).w;
    int r = P.blur;
    // Radius 0 means no blur: its Gaussian would have sigma = r / 2 = 0.
    // Background keeps its input: it has no surface to agree with.
    if (r == 0 || isBackground(d)) {
        write_ao(pixel, vec4(centreAo, 0.0, 0.0, 0.0));
        return;
    }
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;

    float sum = 0.0;
    float totalWeight = 0.0;
    for (int y = -r; y <= r; ++y) {
        for (int x = -r; x <= r; ++x) {
            ivec2 q = pixel + ivec2(x, y);
            // Taps outside the image are skipped rather than clamped, so the
            // edge row is not counted many times over.
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frame.size))) continue;
            float di = texelFetch(in_position, q, 0).w;
            if (isBackground(di)) continue;
            vec3 Ni = texelFetch(in_normal, q, 0).xyz;
            float spatial = gaussianWeight(abs(x)) * gaussianWeight(abs(y));
            float normalWeight = max(0.0, dot(N, Ni));
            float depthWeight = exp(-(d - di) * (d - di) / twoSigma2);
            float W = spatial * normalWeight * depthWeight;
            sum += texelFetch(in_ao, q, 0).r * W;
            totalWeight += W;
        }
    }
    // The spatial kernel sums to one (hence 2·sum − w0 in blur_weights.cpp);
    // whatever weight the depth and normal terms reject goes back to the
    // centre tap. Inside a surface this is the plain Gaussian; at an edge the
    // rejected taps' share stays with the centre, so nothing crosses it. It
    // also keeps the seed's warning true: a kernel that does not sum to one
    // shifts the AO (taps over one give the centre a negative weight).
    float ao = sum + (1.0 - totalWeight) * centreAo;
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
}
