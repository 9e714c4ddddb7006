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
// Which pixel a texel picked is found by applying the pick level by level
// from the texel down, as depth_pyramid.glsl applies it a dispatch at a
// time (clamp included), not by include/pyramid.glsl's closed form: the
// build and the readers' undoing of it stay two statements of the rule, so
// a mistake in one shows against the other.
#include "include/common.glsl"

ivec2 levelSizeOf(int l) {
    return max(frame.size >> l, ivec2(1));
}

// The level-0 pixel texel t of `level` holds.
ivec2 pickedPixel(ivec2 t, int level) {
    for (int k = level; k > 0; --k) t = min(t * 2 + ivec2(t.y & 1, t.x & 1), levelSizeOf(k - 1) - 1);
    return t;
}

void cavity_main(ivec2 pixel) {
    vec4 depth = vec4(texelFetch(in_position, pixel, 0).w, 0.0, 0.0, 0.0);
    write_zmip(pixel, depth);
    // A pixel a texel of level l + 1 picked was picked by its texel of level
    // l on the way (the chain passes through it): the first level that did
    // not pick this pixel, or that has no texel over it (past an odd size),
    // ends its work. Three pixels in four stop at level 1.
    for (int l = 1; l < CAVITY_LEVELS_zmip; ++l) {
        ivec2 t = pixel >> l;
        if (any(greaterThanEqual(t, levelSizeOf(l))) || pickedPixel(t, l) != pixel) break;
        write_zmip_level(l, t, depth);
    }
}
