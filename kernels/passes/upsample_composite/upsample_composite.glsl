// The fused half-resolution tail: the joint bilateral upsample
// (include/upsample.glsl) and the composite (include/composite.glsl) in one
// full-resolution pass, so that a half-resolution frame pays one pass, one
// read of the full-resolution normal and position, and no round trip of the
// full-resolution AO through memory before the composite reads it. It still
// writes that AO (write_ao) for the gate and the quality measure.
//
// The stored AO is upsample_bilateral's, bit for bit. The colour is
// composited from the AO before the R16F store rounds it, so it may differ
// from the two passes' by one 8-bit step where the rounding crosses one
// (a test checks both on both APIs). Rounding it first to match cannot be
// exact: packHalf2x16 rounds to nearest, while an R16F store may round
// towards zero (lavapipe's does: one half-float step on a quarter of the
// pixels).
#include "include/upsample.glsl"
#include "include/composite.glsl"

void cavity_main(ivec2 pixel) {
    upsampleShareTile();
    if (!inImage(pixel)) return;
    vec4 albedo = texelFetch(in_albedo, pixel, 0);
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    float ao = 1.0;
    if (!isBackground(p.w) && lengthSquared(nrm) != 0.0)
        ao = upsampleAo(pixel, p, nrm);
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
    write_color(pixel, compositeColor(pixel, albedo, nrm, ao));
}
