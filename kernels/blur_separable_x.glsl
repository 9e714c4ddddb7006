// The horizontal pass of the separable depth-aware blur
// (include/blur_separable.glsl); keeps the depth key for the vertical pass.
#include "include/blur_separable.glsl"

void cavity_main(ivec2 pixel) {
    write_ao_key(pixel, blurAlong(pixel, ivec2(1, 0)));
}
