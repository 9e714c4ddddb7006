// The horizontal pass of ssdo_fast's separable blur: the key's visibility
// (include/blur_separable.glsl) and the direct radiance beside it, with the
// same weights, so the two stay aligned at every edge as
// blur_bilateral_ssdo.glsl keeps them. Also blurs the bounce (radiance is
// then the indirect light; the key's visibility is blurred again and not
// used).
#define BLUR_ALONG_X 1
#define BLUR_WITH 1
#define BLUR_WITH_IN_TILE 1   // the radiance, tiled beside the key
#include "include/blur_separable.glsl"

vec3 blurredWith(ivec2 q) {
    return texelFetch(in_radiance, q, 0).rgb;
}

void cavity_main(ivec2 pixel) {
    blurShareTile();
    if (!inImage(pixel)) return;
    vec3 radiance;
    write_ao_key(pixel, blurAlong(pixel, radiance));
    write_radiance(pixel, vec4(radiance, 1.0));
}
