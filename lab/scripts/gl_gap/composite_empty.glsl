// The composite reduced to an empty dispatch (lab/scripts/gpu_gl_gap.sh): every
// invocation runs and stores nothing (the store below never happens, and
// keeps the image bound as in every other pass).
#include "include/common.glsl"

void cavity_main(ivec2 pixel) {
    if (pixel.x < 0) write_color(pixel, vec4(0.0));
}
