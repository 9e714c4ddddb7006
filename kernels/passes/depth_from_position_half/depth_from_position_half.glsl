// depth_from_position.glsl for the half-resolution G-buffer: the hardware
// depth at which the half texel's own centre ray meets the surface.
//
// A half texel holds one real full-resolution texel of its 2x2 block
// (downsample_depth.glsl), whose position lies on *that* texel's centre
// ray, half a full texel beside the half texel's in x and y. The hemisphere
// kernel rebuilds positions from depth on the half texel's centre ray
// (viewFromDepth, seed 002), so the borrowed depth put every rebuilt point
// off its surface by the depth's slope over that half texel, one way on
// the nearest-depth texels of the checkerboard and the other way on the
// farthest: on a wall seen obliquely, points a texel apart stood in front
// of and behind each other's planes, and samples near the surface read as
// occluded, a blotchy grey haze over open walls (seen at
// corner/hemisphere/n16/b4/half/320x180). Intersected with the texel's
// tangent plane (its position and normal), the ray finds the surface where
// the kernel will look for it.
//
// Where the plane is seen nearly edge-on the intersection runs far along
// the ray; a move of more than a twentieth of the depth (a plane under about
// 5 degrees to the ray at 320x180, less at larger sizes) keeps the borrowed
// depth instead, as before.
#include "include/screen_space.glsl"

void cavity_main(ivec2 pixel) {
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 n = texelFetch(in_normal, pixel, 0).xyz;
    float depth = 1.0;
    if (!isBackground(p.w)) {
        EXACT vec3 surface = p.xyz;
        vec3 hit;
        if (halfTexelRayHit(pixel, p.xyz, n, hit)) surface = hit;
        EXACT vec4 clip = mulPoint(frame.proj, surface, 1.0);
        EXACT float d = clip.z * portableReciprocal(clip.w);
        depth = d;
    }
    write_depth(pixel, vec4(depth, 0.0, 0.0, 0.0));
}
