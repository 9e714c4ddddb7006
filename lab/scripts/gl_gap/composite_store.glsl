// The composite reduced to its store (lab/scripts/gpu_gl_gap.sh): one RGBA8
// store a pixel, nothing fetched, so that a pass's fixed cost shows.
#include "include/common.glsl"

void cavity_main(ivec2 pixel) {
    write_color(pixel, vec4(vec2(pixel) * 1e-4, 0.5, 1.0));
}
