// The SSDO lit image (Ritschel et al., I3D 2009, "Integration into the
// lighting pass"), diffuse only (the scenes have no specular term), in one
// of two modes (P.ssdo_mode):
//   visibility (0): albedo * ambient(N) * visibility + albedo * L_ind.
//                   ambient(N) is the sky's irradiance / pi from 9
//                   spherical-harmonic coefficients, the seed's "SH
//                   diffuse", scaled by the directional visibility: the
//                   closest to a drop-in for an AO factor.
//   radiance (1):   albedo * (L_dir + L_ind): the per-sample integral of the
//                   open sky replaces the SH term; more exact, and noisier
//                   at the same sample count.
// Background shows the sky, which the direct pass left in its radiance.
// Then the +-0.5/255 IGN dither of composite.glsl against 8-bit banding.
#include "include/common.glsl"
#include "include/noise.glsl"
#include "include/sky.glsl"

void cavity_main(ivec2 pixel) {
    vec4 albedo = texelFetch(in_albedo, pixel, 0);
    vec3 radiance = texelFetch(in_radiance, pixel, 0).rgb;
    vec3 color;
    // Albedo alpha is 1 on every hit and 0 where the ray missed.
    if (albedo.a < 0.5) {
        color = radiance;
    } else {
        vec3 indirect = texelFetch(in_indirect, pixel, 0).rgb;
        if (P.ssdo_mode == 0) {
            float visibility = texelFetch(in_visibility, pixel, 0).r;
            vec3 N = texelFetch(in_normal, pixel, 0).xyz;
            color = albedo.rgb * (skyAmbient(P.sky_sh, N) * visibility + indirect);
        } else {
            color = albedo.rgb * (radiance + indirect);
        }
    }
    if (P.dither != 0) {
        EXACT float offset = (ign(vec2(pixel) + 0.5) - 0.5) * 0.003921569;
        color += vec3(offset);
    }
    write_color(pixel, vec4(clamp(color, 0.0, 1.0), 1.0));
}
