// The depth- and normal-aware (bilateral) blur's taps, for every image it
// blurs: each tap of a (2r+1)^2 Gaussian is further weighted by how much its
// surface agrees with the centre's. Normals more than 90 degrees apart get
// nothing, and the weight falls off as a Gaussian in linear-depth difference
// (McGuire et al., HPG 2011; docs/kernels.md). It smooths the sample noise
// inside a surface without carrying darkness across a silhouette or a crease.
//
// The kernel that includes this defines bilateralAccumulate: what one tap
// adds to its own sums (blur_bilateral.glsl: the AO; blur_bilateral_ssdo.glsl:
// visibility and radiance, which so share every weight and stay aligned at
// every edge).

void bilateralAccumulate(ivec2 q, float W);

// P.weights holds the 1-D Gaussian w[0..r] (blur_weights.cpp), already
// normalised over the full symmetric kernel.
float gaussianWeight(int i) {
    return P.weights[i >> 2][i & 3];
}

// Walks the taps around `pixel` (centre depth d, normal N), handing each its
// weight, and returns the weights' total. The spatial kernel sums to one
// (hence 2·sum − w0 in blur_weights.cpp), so the caller gives what the depth
// and normal terms rejected, 1 − total, back to the centre tap: inside a
// surface this is the plain Gaussian, at an edge the rejected share stays
// with the centre and nothing crosses it. A kernel that does not sum to one
// would shift the AO (taps over one give the centre a negative weight).
float bilateralTaps(ivec2 pixel, int r, float d, vec3 N) {
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;
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
            bilateralAccumulate(q, W);
            totalWeight += W;
        }
    }
    return totalWeight;
}
