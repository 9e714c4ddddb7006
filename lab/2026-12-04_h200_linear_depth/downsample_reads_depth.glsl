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
// The picks compare the G-buffer's linear depth (R32F, the position's w bit
// for bit): 4 bytes a texel, where the positions are 16. Only the chosen
// texel's position and normal are fetched. Besides the half position and
// normal it writes the chosen depth, the half-resolution pyramid's level 0.
//
// frame.size is the half size; the full size is the inputs' own size.
#include "include/common.glsl"

// Background (0) counts as infinitely far, so it wins the max.
float blockDepth(float w) {
    return isBackground(w) ? 3.0e38 : w;
}

void cavity_main(ivec2 pixel) {
    ivec2 full = textureSize(in_linear_depth, 0);
    bool nearest = ((pixel.x + pixel.y) & 1) == 0;
    ivec2 best = min(pixel * 2, full - 1);
    float bestW = texelFetch(in_linear_depth, best, 0).r;
    float bestDepth = blockDepth(bestW);
    // Fixed order and strict comparisons: ties keep the first texel, on the
    // GPU and in the reference alike. Odd full sizes clamp the last block.
    for (int k = 1; k < 4; ++k) {
        ivec2 texel = min(pixel * 2 + ivec2(k & 1, k >> 1), full - 1);
        float w = texelFetch(in_linear_depth, texel, 0).r;
        float d = blockDepth(w);
        if (nearest ? d < bestDepth : d > bestDepth) {
            best = texel;
            bestDepth = d;
            bestW = w;
        }
    }
    write_position_half(pixel, texelFetch(in_position, best, 0));
    write_normal_half(pixel, texelFetch(in_normal, best, 0));
    write_linear_depth_half(pixel, vec4(bestW, 0.0, 0.0, 0.0));
}
