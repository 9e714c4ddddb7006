// The linear-depth pyramid of depth_pyramid.glsl, every level in one
// dispatch. AMD's single-pass downsampler reduces each block through
// workgroup-shared memory, and finishes the last levels in the last
// workgroup to arrive (a global atomic), because a min or a mean needs every
// texel of the block. The pyramid's pick keeps one texel of each 2x2 block,
// so a texel of level l holds exactly one level-0 pixel, inside its own
// 2^l x 2^l block: the thread of that pixel, which has just read its depth
// for level 0, writes it to every level whose texel picked it. No shared
// memory, no barrier, no atomic, and no second read of anything.
//
// Whether it did is checked link by link down the chain, each link the pick
// depth_pyramid.glsl makes a dispatch at a time (clamp included): texel t of
// level k picked, from level k - 1, min(2t + (t.y & 1, t.x & 1), size - 1);
// and the level k - 1 texel on this pixel's chain is pixel >> (k - 1), since
// a pick stays inside its own block. Each texel stores the pixel beside its
// depth; the CPU reference finds it instead by undoing the picks, so the
// build and the undoing stay two statements of one rule, and a mistake in
// one shows against the other.
#include "include/common.glsl"
#include "include/pyramid_build.glsl"

#ifdef CAVITY_INTERLEAVE
// depth_pyramid_layered: level 0 again, split into the AO pass's k x k
// layers (OutputDecl::layered). The last row's and column's threads also
// fill the atlas's padding, which no pixel maps to, so that no texel of it
// is left undefined.
void writeLayers(ivec2 pixel, vec4 depth) {
    write_zlayers(cavityLayerTexel(pixel), depth);
    if (pixel.x < frame.size.x - 1 && pixel.y < frame.size.y - 1) return;
    ivec2 padded = cavityLayerSize() * CAVITY_INTERLEAVE;
    ivec2 last = ivec2(pixel.x == frame.size.x - 1 ? padded.x - 1 : pixel.x,
                       pixel.y == frame.size.y - 1 ? padded.y - 1 : pixel.y);
    for (int y = pixel.y; y <= last.y; ++y)
        for (int x = pixel.x; x <= last.x; ++x)
            if (ivec2(x, y) != pixel) write_zlayers(cavityLayerTexel(ivec2(x, y)), vec4(0.0));
}
#endif

void cavity_main(ivec2 pixel) {
    float depth = texelFetch(in_linear_depth, pixel, 0).r;
    vec4 value = pyramidValue(depth, pixel);
    write_zmip(pixel, value);
#ifdef CAVITY_INTERLEAVE
    writeLayers(pixel, vec4(depth, 0.0, 0.0, 0.0));
#endif
    writePyramidChain(pixel, value);
}
