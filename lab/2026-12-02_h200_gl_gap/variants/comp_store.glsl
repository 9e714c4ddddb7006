// composite reduced to one RGBA8 store per pixel, no fetch.
#include "include/common.glsl"

void cavity_main(ivec2 pixel) {
    write_color(pixel, vec4(vec2(pixel) * 1e-4, 0.5, 1.0));
}
