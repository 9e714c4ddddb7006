// The lit image: a sky-and-ground ambient term, darkened by the AO, on
// albedo; background shows the sky. AO multiplies the whole ambient term
// (McGuire et al., HPG 2011): 1 leaves open surfaces alone, 0 blacks out a
// fully enclosed point. Shared by composite.glsl and upsample_composite.glsl
// (the fused half-resolution tail); a kernel that includes it declares the
// parameter dither.
#include "include/common.glsl"
#include "include/noise.glsl"

const vec3 SKY_COLOR = vec3(0.85, 0.92, 1.0);
const vec3 GROUND_COLOR = vec3(0.55, 0.50, 0.45);

// Hemisphere ambient light: surfaces facing up see the sky, surfaces facing
// down see the ground. View-space +Y stands in for world up because the
// scene cameras are nearly level (sdf_scenes.glsl), which keeps the
// composite independent of any camera matrix.
vec3 ambientLight(vec3 N) {
    return mix(GROUND_COLOR, SKY_COLOR, 0.5 + 0.5 * N.y);
}

// Albedo alpha is 1 on every hit and 0 where the ray missed.
bool isSky(vec4 albedo) { return albedo.a < 0.5; }

// The colour the 8-bit target stores at `pixel`: the sky where isSky(albedo),
// else albedo x ambient x ao; then the dither, clamped to [0, 1].
vec4 compositeColor(ivec2 pixel, vec4 albedo, vec3 N, float ao) {
    vec3 color = isSky(albedo) ? SKY_COLOR : albedo.rgb * ambientLight(N) * ao;
    // An 8-bit target has 256 levels, and the slow gradients of blurred AO
    // band visibly between them; +-half a level of IGN dither turns the
    // bands into noise too fine to see (the hemisphere SSAO lesson (docs/kernels.md)).
    if (P.dither != 0) {
        EXACT float offset = (ign(vec2(pixel) + 0.5) - 0.5) * 0.003921569;   // 1/255
        color += vec3(offset);
    }
    return vec4(clamp(color, 0.0, 1.0), 1.0);
}
