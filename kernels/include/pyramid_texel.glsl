// What a texel of the linear-depth pyramid holds (RG32F): the depth it
// picked, and the level-0 pixel that depth came from, so that a reader
// rebuilds the sample's position on that pixel's ray without undoing the
// picks (include/pyramid.glsl). Written by every build
// (include/pyramid_build.glsl, depth_pyramid.glsl), read by the fast kernels.
//
// The pixel's bits go in the second channel as they are: x in bits 0-14, y
// in bits 15-29, and bit 30 set, which keeps the float's exponent field
// between 128 and 254 for any image under 32512 rows (the harness takes at
// most 16384 a side): never a NaN, an infinity or a denormal that an
// implementation could flush on the way.
// A copy from texel to texel (the per-level build) moves the bits unchanged.
vec4 pyramidValue(float depth, ivec2 source) {
    return vec4(depth, intBitsToFloat(0x40000000 | (source.y << 15) | source.x), 0.0, 0.0);
}

ivec2 pyramidSourceOf(float packed) {
    int bits = floatBitsToInt(packed);
    return ivec2(bits & 0x7FFF, (bits >> 15) & 0x7FFF);
}
