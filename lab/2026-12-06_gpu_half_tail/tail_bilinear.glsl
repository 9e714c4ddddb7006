// Study variant (lab 2026-12-06_gpu_half_tail), in place of
// passes/upsample_composite/upsample_composite.glsl: the half-resolution AO
// upsampled bilinearly, with no edge weights, so that the pass reads no
// full-resolution position and no half-resolution position or normal. The
// background is told by its zero normal (gbuffer_sdf writes one there).
#include "include/composite.glsl"

void cavity_main(ivec2 pixel) {
    if (!inImage(pixel)) return;
    vec4 albedo = texelFetch(in_albedo, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    float ao = 1.0;
    if (lengthSquared(nrm) != 0.0) {
        ivec2 last = textureSize(in_ao_half, 0) - 1;
        vec2 c = vec2(pixel) * 0.5 - 0.25;
        ivec2 b = ivec2(floor(c));
        vec2 f = c - vec2(b);
        float a00 = texelFetch(in_ao_half, clamp(b, ivec2(0), last), 0).r;
        float a10 = texelFetch(in_ao_half, clamp(b + ivec2(1, 0), ivec2(0), last), 0).r;
        float a01 = texelFetch(in_ao_half, clamp(b + ivec2(0, 1), ivec2(0), last), 0).r;
        float a11 = texelFetch(in_ao_half, clamp(b + ivec2(1, 1), ivec2(0), last), 0).r;
        ao = mix(mix(a00, a10, f.x), mix(a01, a11, f.x), f.y);
    }
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
    write_color(pixel, compositeColor(pixel, albedo, nrm, ao));
}
