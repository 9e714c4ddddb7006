// The vertical pass of ssdo_fast's separable blur
// (blur_separable_ssdo_x.glsl): the blurred visibility, as every blur writes
// it, and the blurred radiance.
#define BLUR_WITH 1   // the radiance, fetched a tap (include/blur_separable.glsl says why)
#include "include/blur_separable.glsl"

vec3 blurredWith(ivec2 q) {
    return texelFetch(in_radiance, q, 0).rgb;
}

void cavity_main(ivec2 pixel) {
    blurShareTile();
    if (!inImage(pixel)) return;
    vec3 radiance;
    write_visibility(pixel, vec4(blurAlong(pixel, radiance).r, 0.0, 0.0, 0.0));
    write_radiance(pixel, vec4(radiance, 1.0));
}
