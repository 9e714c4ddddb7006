// What a texel of the linear-depth pyramid holds: one 32-bit float (R32F),
// the depth it picked with the level-0 pixel that depth came from packed
// into the low bits of its mantissa, so that a reader rebuilds the sample's
// position on that pixel's ray from one 4-byte fetch, without undoing the
// picks (include/pyramid.glsl). Written by every build
// (include/pyramid_build.glsl, depth_pyramid.glsl), read by the fast kernels.
// A texel of 8 bytes (the depth beside the pixel) is fetched at half the
// rate of a 4-byte one on the GPUs we measure, and the fast kernels' AO
// passes are bound by that rate (study 2026-12-06_gpu_packed_texel).
//
// Texel t of level l covers the 2^l x 2^l block of level-0 pixels from
// t << l, and its source pixel lies in that block. The source's offset in
// the block, n = min(l, PYRAMID_OFFSET_BITS) bits per axis, replaces the
// low 2n bits of the depth's mantissa: x in bits 0 .. n-1, y in n .. 2n-1.
// What that costs:
//  * the depth: its mantissa keeps 23 - 2n bits, so it is read up to
//    2^(2n - 23) of itself too far (never nearer), at most 2^-13 (1.2e-4 of
//    the depth) at level 5 and below, and nothing at level 0, where the
//    source is the texel itself and nothing is packed;
//  * the source: exact up to level PYRAMID_OFFSET_BITS; a deeper level
//    keeps the offset's top n bits, so its source is the first pixel of a
//    2^(l - n) block (the pipelines build 5 levels, 0 to 4, all exact).
// The background (depth 0) is stored as 0: bits under a zero exponent would
// make a denormal that an implementation may flush, or read as a surface.
// Only integer operations touch the bits, so the CPU reference
// (harness/reference/pyramid.h) follows bit for bit.
const int PYRAMID_OFFSET_BITS = 5;

float pyramidValue(float depth, ivec2 source, int level) {
    int n = min(level, PYRAMID_OFFSET_BITS);
    ivec2 offset = (source & ((1 << level) - 1)) >> (level - n);
    int bits = (floatBitsToInt(depth) & ~((1 << (2 * n)) - 1)) | offset.x | (offset.y << n);
    return depth > 0.0 ? intBitsToFloat(bits) : depth;
}

// The level-0 pixel whose depth texel t of `level` holds (`packed`).
ivec2 pyramidSourceOf(float packed, ivec2 t, int level) {
    int n = min(level, PYRAMID_OFFSET_BITS);
    int bits = floatBitsToInt(packed);
    ivec2 offset = ivec2(bits, bits >> n) & ((1 << n) - 1);
    return (t << level) | (offset << (level - n));
}
