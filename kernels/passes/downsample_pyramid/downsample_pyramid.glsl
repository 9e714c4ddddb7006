// The half-resolution G-buffer and its linear-depth pyramid in one pass:
// downsample_depth.glsl's picks, with the chosen depth written as the
// pyramid's level 0 and, by the thread that chose it, to every smaller level
// whose texel picked it (include/pyramid_build.glsl, as depth_pyramid_single
// does from a depth image). A half-resolution frame of a fast kernel then
// launches one pass here instead of two, and neither writes nor reads back
// the half-resolution depth in between. The images are those of
// downsample_depth followed by depth_pyramid_single, bit for bit: the same
// picks, and the depth is a copy.
#include "include/downsample.glsl"
#include "include/pyramid_build.glsl"

void cavity_main(ivec2 pixel) {
    ivec2 best = downsamplePick(pixel);
    vec4 p = texelFetch(in_position, best, 0);
    vec4 n = texelFetch(in_normal, best, 0);
    write_position_half(pixel, p);
    write_normal_half(pixel, n);
    vec4 value = pyramidValue(halfRayDepth(pixel, p, n.xyz), pixel);
    write_zmip(pixel, value);
    writePyramidChain(pixel, value);
}
