// Joint bilateral upsample of half-resolution AO (seed the hemisphere SSAO lesson (docs/kernels.md)
// exercise 5; seed McGuire et al., HPG 2011 on the halos a plain upsample
// leaves at silhouettes): the weights are include/upsample.glsl's.
#include "include/upsample.glsl"

void cavity_main(ivec2 pixel) {
    upsampleShareTile();
    if (!inImage(pixel)) return;
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    if (isBackground(p.w) || lengthSquared(nrm) == 0.0) {
        write_ao(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    write_ao(pixel, vec4(upsampleAo(pixel, p, nrm), 0.0, 0.0, 0.0));
}
