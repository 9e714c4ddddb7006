// Reading the linear-depth pyramid (depth_pyramid.glsl): the fast AO
// kernels' shared helpers, mirrored by harness/reference/ref_fast.cpp.
#include "include/screen_space.glsl"
#include "include/pyramid_texel.glsl"

// Samples up to 2^(3 + 1) = 16 px away read level 0; each doubling of the
// distance moves one level down (after Scalable Ambient Obscurance).
const int LOG_MAX_OFFSET = 3;

// viewRayAt(pixel) * depth with each operation rounded as the CPU's is: the
// rebuilt positions feed discrete decisions (a radius or a depth test).
// A kernel that defines CAVITY_FMA_POSITIONS gets, with the GPU's own
// arithmetic (CAVITY_INEXACT), the ray as one fused multiply-add of the
// pixel instead: (pixel + 0.5) * 2 / size - 1 folded into a scale and an
// offset. On the H200 that made alchemy_fast's AO pass faster on both APIs,
// and alchemy_fast asks for it. hemisphere_fast does not: faster on Vulkan,
// slower on GL, and a kernel whose images differ between the APIs by a
// flipped ray fails the CPU-baseline gate on one of them
// (study 2026-12-04_h200_pyramid_sources).
vec3 positionAt(ivec2 pixel, float depth) {
#if defined(CAVITY_INEXACT) && defined(CAVITY_FMA_POSITIONS)
    vec2 camera = vec2(frame.camera.x, -frame.camera.y);
    vec2 ray = fma(vec2(pixel), 2.0 * frame.invSize * camera, (frame.invSize - 1.0) * camera);
    return vec3(ray * depth, -depth);
#else
    EXACT vec2 ndc = (vec2(pixel) + 0.5) * frame.invSize * 2.0 - 1.0;
    EXACT vec3 p = vec3(ndc.x * frame.camera.x * depth, -ndc.y * frame.camera.y * depth, -depth);
    return p;
#endif
}

// The size of pyramid level l: level 0 is this pass's size, and each mip
// halves it, rounding down. Not textureSize(in_zmip, l): llvmpipe answers that
// query with one lane's lod for every lane when l varies across them, which
// clamped samples of level-0 pixels into a neighbour's level-1 size.
ivec2 levelSize(int l) {
    return max(frame.size >> l, ivec2(1));
}

// The level a sample `h` pixels from its receiver reads (h >= 0).
int pyramidLevel(int h, int maxLevel) {
    return clamp(findMSB(h) - LOG_MAX_OFFSET, 0, maxLevel);
}

// The first "tiny" level: the first whose level above is at most 1 texel
// across (frame.size >> (l - 1) <= 1 in x or y), which only small images
// reach within their samples' levels. Below it every level is at least 1
// texel across and the level above at least 2. A function of the frame
// alone, so a kernel asks once per pixel (PyramidView::tiny).
int pyramidTinyLevel() {
    return min(findMSB(frame.size.x), findMSB(frame.size.y)) + 1;
}

// The texel of `level` that covers the in-image pixel s. `tiny`:
// pyramidTinyLevel(). Below the tiny levels a level's size is
// frame.size >> level (levelSize's max() never acts); choosing the path
// once per sample, with `tiny` computed once per pixel, and a constant
// there (belowTiny) drops the other path at compile time.
ivec2 pyramidTexel(ivec2 s, int level, int tiny) {
    // tiny >= 32: no level can be a tiny one (level <= 28).
    if (tiny >= 32 || level < tiny) return min(s >> level, (frame.size >> level) - 1);
    return min(s >> level, levelSize(level) - 1);
}

// What projecting a view-space point onto this pass's pixels takes:
// x_px = x / depth * toPixel.x + size.x / 2, and y likewise with the flip
// (positionAt() inverted); and the pyramid's last level.
// The depth of texel t of level l. Level 0 comes from the interleaved
// layers where the kernel runs in k x k > 1 of them (an input "zlayers",
// KernelDecl::interleaved): the same value, at the texel where the warp's
// neighbours read theirs. With k = 1 the layer is level 0 itself, and the
// branch is compiled out.
float pyramidDepth(ivec2 t, int level) {
#if defined(CAVITY_INTERLEAVE) && CAVITY_INTERLEAVE > 1
    if (level == 0) return texelFetch(in_zlayers, cavityLayerTexel(t), 0).r;
#endif
    return texelFetch(in_zmip, t, level).r;
}

// The depth of texel t of `level`, and (`source`) the level-0 pixel it came
// from, which the texel stores beside it (include/pyramid_texel.glsl): one
// fetch, and no undoing of the picks, which took a fifth of alchemy_fast's
// AO pass as a shift and two masks. Level 0 of the interleaved layers holds
// the depth alone, and there the source is t itself.
float pyramidFetch(ivec2 t, int level, out ivec2 source) {
#if defined(CAVITY_INTERLEAVE) && CAVITY_INTERLEAVE > 1
    if (level == 0) {
        source = t;
        return texelFetch(in_zlayers, cavityLayerTexel(t), 0).r;
    }
#endif
    vec2 texel = texelFetch(in_zmip, t, level).rg;
    source = pyramidSourceOf(texel.y);
    return texel.x;
}

struct PyramidView {
    vec2 toPixel;
    vec2 centre;
    int maxLevel;
    int tiny;   // pyramidTinyLevel()
};

PyramidView pyramidView() {
    EXACT vec2 toPixel = vec2(0.5, -0.5) * vec2(frame.size) *
                           vec2(portableReciprocal(frame.camera.x), portableReciprocal(frame.camera.y));
    return PyramidView(toPixel, 0.5 * vec2(frame.size), textureQueryLevels(in_zmip) - 1, pyramidTinyLevel());
}

// The same view, saying that every level is below the tiny ones: for a
// copy of a loop that a kernel takes when v.maxLevel < v.tiny.
PyramidView belowTiny(PyramidView v) {
    return PyramidView(v.toPixel, v.centre, v.maxLevel, 32);
}

// The stored surface under the view-space point s, seen from the receiver
// at `pixel`: false for a point behind the camera plane, off the screen or
// on the background. Samples far from the pixel read coarser levels
// (pyramidLevel). `source` and `zq`: the level-0 pixel whose depth the
// level holds, and that depth (the stored point is positionAt(source, zq)).
bool pyramidLookup(PyramidView v, vec3 s, ivec2 pixel, out ivec2 source, out float zq) {
    source = ivec2(-1);
    zq = 0.0;
    if (s.z >= 0.0) return false;
    EXACT vec2 sp = s.xy * portableReciprocal(-s.z) * v.toPixel + v.centre;
    ivec2 texel = ivec2(floor(clamp(sp, vec2(-1.0), vec2(frame.size))));
    // One unsigned test for both sides: a negative texel wraps past any size.
    if (any(greaterThanEqual(uvec2(texel), uvec2(frame.size)))) return false;
    ivec2 away = abs(texel - pixel);
    int level = pyramidLevel(max(away.x, away.y), v.maxLevel);
    zq = pyramidFetch(pyramidTexel(texel, level, v.tiny), level, source);
    if (isBackground(zq)) return false;
    return true;
}

// Whether the point s, sampled from the receiver with unit normal N at the
// level `receiverLevel` = N . X along it (X its view point), is blocked, and
// by which stored point q (pyramidLookup's source and zq). No normal is
// fetched at q; two tests, both along N (ssao_hemisphere_fast.glsl says
// why):
//  * q rises above s: N . q - N . s > bias, with N . q = z_q (N . ray_q).
//    The receiver's own plane sits at the receiver's level under every
//    point, at any viewing angle: no self-shadowing.
//  * s lies behind q along its own ray (z_q + bias < z_s) while q stands
//    above the receiver's tangent plane, N . q - N . X > bias: the verdict
//    of a depth layer for a point that has passed under or through a thin
//    occluder seen from above (a slat, a plate over a gap), which rises no
//    higher than the point and so passes the first test. The receiver's own
//    plane never stands above itself, so this cannot shadow it either.
// Where q's ray meets the receiver's plane from behind (N . ray_q >= 0, a
// receiver seen edge-on, such as a sphere's rim over the floor) N . q says
// nothing, and the depth test alone decides, the seed's where q has no
// normal.
bool pyramidBlocks(PyramidView v, vec3 N, float receiverLevel, vec3 s, ivec2 pixel, float bias, out ivec2 source,
                   out float zq) {
    if (!pyramidLookup(v, s, pixel, source, zq)) return false;
    float along = orderedDot(N, positionAt(source, 1.0));
    EXACT float height = zq * along;
    EXACT float rise = height - orderedDot(N, s);
    if (along < 0.0 && rise > bias) return true;
    EXACT float threshold = zq + bias;
    if (threshold >= -s.z) return false;
    EXACT float lift = height - receiverLevel;
    return along >= 0.0 || lift > bias;
}
