// Depth- and normal-aware (bilateral) blur of the raw AO; the taps and their
// weights are include/blur_bilateral.glsl's.
#include "include/common.glsl"
#include "include/blur_bilateral.glsl"

float sum = 0.0;

void bilateralAccumulate(ivec2 q, float W) {
    sum += texelFetch(in_ao, q, 0).r * W;
}

void cavity_main(ivec2 pixel) {
    float centreAo = texelFetch(in_ao, pixel, 0).r;
    float d = texelFetch(in_position, pixel, 0).w;
    int r = P.blur;
    // Radius 0 means no blur: its Gaussian would have sigma = r / 2 = 0.
    // Background keeps its input: it has no surface to agree with.
    if (r == 0 || isBackground(d)) {
        write_ao(pixel, vec4(centreAo, 0.0, 0.0, 0.0));
        return;
    }
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    float totalWeight = bilateralTaps(pixel, r, d, N);
    float ao = sum + (1.0 - totalWeight) * centreAo;
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
}
