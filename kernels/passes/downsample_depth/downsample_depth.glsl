// Depth-aware 2x2 downsample of the G-buffer for half-resolution AO. Seed
// McGuire et al., HPG 2011 warns that upsampled half-resolution AO leaves
// halos at silhouettes; averaging positions across a depth edge would make
// it worse, inventing surfaces floating between foreground and background.
// So each half texel copies one real full-resolution texel of its 2x2 block.
//
// Which one: a checkerboard of min and max depth (half texels with even
// x + y take the nearest texel of their block, odd ones the farthest). Every
// 2x2 neighbourhood of half texels then holds both sides of an edge that
// crosses it, so the bilateral upsample (upsample_bilateral.glsl), which
// looks at the 4 half texels around each full pixel, finds a depth match for
// the pixels on either side. Taking the minimum everywhere would lose the far
// side: thin gaps and background pixels next to silhouettes would have only
// foreground half texels to choose from.
//
// The picks compare the positions' w, whose texels the copy then reads
// again from cache. Comparing the G-buffer's linear depth instead (R32F, a
// quarter of the bytes) and fetching the chosen position and normal after
// made this pass slower on the H200, both APIs: the chosen texel's
// position was then a second trip to memory
// (study 2026-12-04_h200_linear_depth). Beside the half position and
// normal it writes the chosen texel's depth moved onto the half texel's own
// ray (halfRayDepth, include/downsample.glsl), the half-resolution
// pyramid's level 0,
// for a pipeline that builds that pyramid in a pass of its own
// (downsample_pyramid.glsl builds it here).
//
// frame.size is the half size; the full size is the inputs' own size.
#include "include/downsample.glsl"

void cavity_main(ivec2 pixel) {
    ivec2 best = downsamplePick(pixel);
    vec4 p = texelFetch(in_position, best, 0);
    vec4 n = texelFetch(in_normal, best, 0);
    write_position_half(pixel, p);
    write_normal_half(pixel, n);
    write_linear_depth_half(pixel, vec4(halfRayDepth(pixel, p, n.xyz), 0.0, 0.0, 0.0));
}
