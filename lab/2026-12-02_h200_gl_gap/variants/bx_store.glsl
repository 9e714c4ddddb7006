// blur_separable_x reduced to one RGBA16F store per pixel, no fetch.
#include "include/blur_separable.glsl"

void cavity_main(ivec2 pixel) {
    write_ao_key(pixel, vec4(vec2(pixel) * 1e-4, 0.5, 0.25));
}
