// Joint bilateral upsample of half-resolution AO (seed the hemisphere SSAO lesson (docs/kernels.md)
// exercise 5; seed McGuire et al., HPG 2011 on the halos a plain upsample
// leaves at silhouettes). Each full-resolution pixel blends the 4 half texels
// around it with
//
//     w_i = bilinear_i * exp(-0.5 * (|N . (Q_i - P)| / (tol * z))^2) * max(0, N . N_i)^8
//
// P, N, z: the full pixel's view position, normal and linear depth; Q_i, N_i:
// half texel i's (copied by downsample_depth, so real surface points);
// tol: P.upsample_depth_tolerance. The depth term measures Q_i's distance
// from P's tangent plane rather than the plain depth difference: on a floor
// seen at a grazing angle depth changes fast from texel to texel though the
// surface is one plane, and the plane distance is 0 there at any slope. It is
// relative to z because the texel footprint grows with depth. The normal
// term keeps a floor from borrowing a wall's AO at a crease, where the plane
// distance is small. If every weight vanishes (a pixel whose surface no half
// texel kept), the half texel nearest in depth is taken as it is.
#include "include/screen_space.glsl"

void cavity_main(ivec2 pixel) {
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    if (isBackground(p.w) || lengthSquared(nrm) == 0.0) {
        write_ao(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    ivec2 halfSize = textureSize(in_ao_half, 0);
    // The full pixel centre (pixel + 0.5) in half-texel units, minus the half
    // texel centre offset: pixel / 2 - 0.25, exact in float.
    vec2 c = vec2(pixel) * 0.5 - 0.25;
    ivec2 base = ivec2(floor(c));
    vec2 f = c - vec2(base);
    float tol = P.upsample_depth_tolerance * p.w;

    float sum = 0.0, weightSum = 0.0;
    float fallback = 1.0, fallbackDist = 3.0e38;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 texel = clamp(base + o, ivec2(0), halfSize - 1);
        float ao = texelFetch(in_ao_half, texel, 0).r;
        vec4 q = texelFetch(in_position_half, texel, 0);
        vec3 m = texelFetch(in_normal_half, texel, 0).xyz;
        if (isBackground(q.w)) continue;   // background holds no AO for a surface
        float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float planeDist = abs(orderedDot(nrm, q.xyz - p.xyz)) / tol;
        float depthWeight = exp(-0.5 * planeDist * planeDist);
        float cn = max(orderedDot(nrm, m), 0.0);
        cn *= cn;
        cn *= cn;
        float normalWeight = cn * cn;
        float w = bilinear * depthWeight * normalWeight;
        sum += w * ao;
        weightSum += w;
        float dz = abs(q.w - p.w);
        if (dz < fallbackDist) {
            fallbackDist = dz;
            fallback = ao;
        }
    }
    float ao = weightSum > 1e-5 ? sum / weightSum : fallback;
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
}
