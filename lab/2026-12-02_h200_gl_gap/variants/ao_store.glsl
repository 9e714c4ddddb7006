// alchemy_fast's AO pass reduced to its two stores (R16F, RGBA16F), no fetch.
#include "include/common.glsl"

void cavity_main(ivec2 pixel) {
    write_ao(pixel, vec4(float(pixel.x) * 1e-4));
    write_ao_key(pixel, vec4(vec2(pixel) * 1e-4, 0.5, 0.25));
}
