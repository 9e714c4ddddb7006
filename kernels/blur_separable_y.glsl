// The vertical pass of the separable depth-aware blur
// (include/blur_separable.glsl): the blurred AO, as every blur writes it.
#include "include/blur_separable.glsl"

void cavity_main(ivec2 pixel) {
    write_ao(pixel, vec4(blurAlong(pixel, ivec2(0, 1)).r, 0.0, 0.0, 0.0));
}
