// The bilateral blur of blur_bilateral.glsl applied to both SSDO outputs in
// one pass, as SSDO (Ritschel et al., I3D 2009) extends its SSAO blur to the
// two render targets: visibility and radiance share every weight
// (include/blur_bilateral.glsl), so the two stay aligned at every edge.
#include "include/common.glsl"
#include "include/blur_bilateral.glsl"

float visSum = 0.0;
vec3 radSum = vec3(0.0);

void bilateralAccumulate(ivec2 q, float W) {
    visSum += texelFetch(in_visibility, q, 0).r * W;
    radSum += texelFetch(in_radiance, q, 0).rgb * W;
}

void cavity_main(ivec2 pixel) {
    float centreVis = texelFetch(in_visibility, pixel, 0).r;
    vec3 centreRad = texelFetch(in_radiance, pixel, 0).rgb;
    float d = texelFetch(in_position, pixel, 0).w;
    int r = P.blur;
    if (r == 0 || isBackground(d)) {
        write_visibility(pixel, vec4(centreVis, 0.0, 0.0, 0.0));
        write_radiance(pixel, vec4(centreRad, 1.0));
        return;
    }
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    // As blur_bilateral.glsl: whatever weight the depth and normal terms
    // reject stays with the centre tap.
    float kept = 1.0 - bilateralTaps(pixel, r, d, N);
    write_visibility(pixel, vec4(visSum + kept * centreVis, 0.0, 0.0, 0.0));
    write_radiance(pixel, vec4(radSum + kept * centreRad, 1.0));
}
