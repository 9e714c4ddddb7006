// The vertical pass of the separable depth-aware blur
// (include/blur_separable.glsl): the blurred AO, as every blur writes it.
#include "include/blur_separable.glsl"

vec3 blurredWith(ivec2 q) {
    return vec3(0.0);
}

void cavity_main(ivec2 pixel) {
    blurShareTile();
    if (!inImage(pixel)) return;
    vec3 unused;
    write_ao(pixel, vec4(blurAlong(pixel, unused).r, 0.0, 0.0, 0.0));
}
