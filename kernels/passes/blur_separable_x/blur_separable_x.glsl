// The horizontal pass of the separable depth-aware blur
// (include/blur_separable.glsl); keeps the depth key for the vertical pass.
#define BLUR_ALONG_X 1
#include "include/blur_separable.glsl"

vec3 blurredWith(ivec2 q) {
    return vec3(0.0);
}

void cavity_main(ivec2 pixel) {
    blurShareTile();
    if (!inImage(pixel)) return;
    vec3 unused;
    write_ao_key(pixel, blurAlong(pixel, unused));
}
