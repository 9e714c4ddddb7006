// The hardware depth value a raster G-buffer pass would have written,
// (proj p).z / (proj p).w in [0, 1], from the ray-marched view position. It
// lets the hemisphere kernel reconstruct positions from depth with
// frame.invProj exactly as the hemisphere SSAO lesson (docs/kernels.md) teaches, whichever
// G-buffer pass ran. Background (position.w = 0) gets 1.0, the cleared depth.
#include "include/screen_space.glsl"

void cavity_main(ivec2 pixel) {
    vec4 p = texelFetch(in_position, pixel, 0);
    float depth = 1.0;
    if (!isBackground(p.w)) {
        // clip.w = -z > 0 in front of the camera. Exact ops, so the depth the
        // hemisphere reference is given matches this one bit for bit.
        EXACT vec4 clip = mulPoint(frame.proj, p.xyz, 1.0);
        EXACT float d = clip.z * portableReciprocal(clip.w);
        depth = d;
    }
    write_depth(pixel, vec4(depth, 0.0, 0.0, 0.0));
}
