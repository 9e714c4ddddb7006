// 4x4 box blur of the hemisphere AO (seed the hemisphere SSAO lesson (docs/kernels.md), "Box
// blur"). The raw AO repeats with the 4x4 rotation tile; a window of exactly
// one tile period holds every rotation once, so the pattern averages out to
// the underlying signal. A Gaussian would weight the tile unevenly and leave
// some of the pattern behind, which is why this is a box.
//
// The seed samples at offsets -1.5..+1.5 texels around the centre, i.e. four
// whole texels per axis; with integer fetches those are x in [px-2, px+1],
// y in [py-2, py+1].
void cavity_main(ivec2 pixel) {
    ivec2 size = textureSize(in_ao, 0);
    // At the border the window slides inwards instead of repeating the edge
    // texel, so it still spans one whole tile period and the tile cancels up
    // to the image edge (images narrower than 4 texels clamp).
    ivec2 start = clamp(pixel - 2, ivec2(0), max(size - 4, ivec2(0)));
    float sum = 0.0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            sum += texelFetch(in_ao, min(start + ivec2(x, y), size - 1), 0).r;
    write_ao(pixel, vec4(sum / 16.0, 0.0, 0.0, 0.0));
}
