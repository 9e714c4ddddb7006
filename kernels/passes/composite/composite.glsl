// The lit image (include/composite.glsl): albedo x sky/ground ambient x AO.
#include "include/composite.glsl"

void cavity_main(ivec2 pixel) {
    vec4 albedo = texelFetch(in_albedo, pixel, 0);
    float ao = 1.0;
    vec3 N = vec3(0.0);
    if (!isSky(albedo)) {
        ao = texelFetch(in_ao, pixel, 0).r;
        N = texelFetch(in_normal, pixel, 0).xyz;
    }
    write_color(pixel, compositeColor(pixel, albedo, N, ao));
}
