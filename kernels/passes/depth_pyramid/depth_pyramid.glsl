// The linear-depth pyramid the fast AO kernels read (after Scalable Ambient
// Obscurance, McGuire, Mara and Luebke, HPG 2012): camera-space depth in one
// RG32F image with a mip chain, so a sample far from its pixel reads a small
// level that stays in cache instead of a texel of a 1080p RGBA32F position
// image that does not. Beside each depth, the level-0 pixel it came from
// (include/pyramid_texel.glsl): a reader rebuilds the position on that
// pixel's ray from the one fetch.
//
// Level 0 is the G-buffer's linear depth (its R32F image, the position's w
// bit for bit; 0 stays background) beside each pixel's own coordinates.
// Level l > 0 keeps one real depth of each 2x2 block of level l - 1 rather
// than a mean or a min: a mean across a silhouette is a surface that is not
// there, which the AO would read as an occluder floating in the gap. Which
// texel of the block alternates with the parity of the other coordinate,
// (2x + (y & 1), 2y + (x & 1)), a rotated grid, so a level does not keep
// only the top-left texel of every block and lose thin features along one
// row or column. The chosen texel is clamped into an odd-sized level.
#include "include/common.glsl"
#include "include/pyramid_texel.glsl"

void cavity_main(ivec2 pixel) {
    if (frame.level == 0) {
        write_zmip(pixel, pyramidValue(texelFetch(in_linear_depth, pixel, 0).r, pixel));
        return;
    }
    ivec2 above = textureSize(in_zmip, frame.level - 1);
    ivec2 pick = min(pixel * 2 + ivec2(pixel.y & 1, pixel.x & 1), above - 1);
    write_zmip(pixel, vec4(texelFetch(in_zmip, pick, frame.level - 1).rg, 0.0, 0.0));
}
