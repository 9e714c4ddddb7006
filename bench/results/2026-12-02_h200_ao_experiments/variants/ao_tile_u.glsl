// Alchemy ambient obscurance on the linear-depth pyramid: the estimator of
// ssao_alchemy.glsl (000_79d41de70034b569.txt) sample for sample, the same
// spiral, falloff, bias and contrast, but each sample's position is rebuilt
// from one 32-bit depth (depth_pyramid.glsl) instead of read as an RGBA32F
// texel: a quarter of the bytes, and for samples far from the pixel a
// coarser level, whose texels neighbouring pixels share in cache.
//
// The level grows with the sample's distance h from the pixel in pixels, as
// in Scalable Ambient Obscurance: level floor(log2 h) - 3, so samples within
// 16 px read level 0 and each doubling of h moves one level down. A texel of
// level l holds the depth of one real pixel up to 2^l pixels from the
// sample's, and the position is rebuilt on that pixel's ray, found by
// undoing the pyramid's picks: the sample is a true surface point, moved by
// under 2^l px in a disc of h >= 2^(l+3) px. Rebuilt on the sample's own ray
// instead, the borrowed depth puts a point off the surface by the depth
// change across 2^l px, which on a wall seen at a grazing angle is far over
// the bias: streaks of missing and false occlusion showed there.
//
// A second output packs AO with the pixel's linear depth and its normal
// (octahedral) in one RGBA16F texel, all the separable blur reads per tap.
#include "include/common.glsl"
#include "include/noise.glsl"
#include "include/octahedral.glsl"
#include "include/alchemy_spiral.glsl"

// Samples up to 2^(3 + 1) = 16 px away read level 0.
const int LOG_MAX_OFFSET = 3;

// viewRayAt(pixel) * depth with each operation rounded as the CPU's is: the
// rebuilt positions feed the |w| <= R test, a discrete decision.
vec3 positionAt(ivec2 pixel, float depth) {
    precise vec2 ndc = (vec2(pixel) + 0.5) * frame.invSize * 2.0 - 1.0;
    precise vec3 p = vec3(ndc.x * frame.camera.x * depth, -ndc.y * frame.camera.y * depth, -depth);
    return p;
}

// The size of pyramid level l: level 0 is this pass's size, and each mip
// halves it, rounding down. Not textureSize(in_zmip, l): llvmpipe answers that
// query with one lane's lod for every lane when l varies across them, which
// clamped samples of level-0 pixels into a neighbour's level-1 size.
ivec2 levelSize(int l) {
    return max(frame.size >> l, ivec2(1));
}

// The level-0 pixel whose depth texel t of `level` holds: depth_pyramid.glsl's
// pick, (2x + (y & 1), 2y + (x & 1)) clamped into the level above, once per level.
ivec2 sourcePixel(ivec2 t, int level) {
    for (int k = level; k > 0; --k) t = min(t * 2 + ivec2(t.y & 1, t.x & 1), levelSize(k - 1) - 1);
    return t;
}

void cavity_main(ivec2 pixel) {
    float d = texelFetch(in_zmip, pixel, 0).r;
    if (isBackground(d)) {
        write_ao(pixel, vec4(1.0));
        write_ao_key(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    vec3 X = positionAt(pixel, d);
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    int maxLevel = textureQueryLevels(in_zmip) - 1;

    int n = P.samples;
    float R = P.radius;
    float c = 0.1 * R;
    float weight = 2.0 * PI * c / float(n);
    float discScale = spiralDiscScale(R, n, d);
    float u = pixelHash(pixel >> 3);
    vec2 fragCentre = vec2(pixel) + 0.5;

    float S = 0.0;
    for (int i = 0; i < n; ++i) {
        float h;
        ivec2 s = spiralSample(i, u, discScale, fragCentre, h);
        if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, frame.size))) continue;
        // h < 2^31 here: the sample is inside the image.
        int level = clamp(findMSB(int(h)) - LOG_MAX_OFFSET, 0, maxLevel);
        ivec2 t = min(s >> level, levelSize(level) - 1);
        float zs = texelFetch(in_zmip, t, level).r;
        if (isBackground(zs)) continue;

        precise vec3 omega = positionAt(sourcePixel(t, level), zs) - X;
        float omega2 = lengthSquared(omega);
        if (omega2 > R * R) continue;
        S += weight * max(0.0, dot(N, omega) - P.bias) / max(c * c, omega2);
    }
    float A = pow(max(0.0, 1.0 - P.scale * S), P.contrast);
    write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));
    write_ao_key(pixel, vec4(A, d, octEncode(N)));
}
