// blur_separable_x reduced to one fetch and one RGBA16F store per pixel.
#include "include/blur_separable.glsl"

void cavity_main(ivec2 pixel) {
    write_ao_key(pixel, texelFetch(in_ao_key, pixel, 0));
}
