// Screen-space directional occlusion, direct pass (Ritschel, Grosch &
// Seidel 2009, as taught in Ritschel et al., I3D 2009). One loop over n
// hemisphere directions gives two outputs:
//   visibility: the luminance-weighted fraction of the sky's energy that
//               reaches the surface, shaped by `contrast` (an AO, 1 = open);
//   radiance:   L_dir = sum over visible directions of
//               (1/pi) L_in cos(theta) (2 pi / n), the sky light that gets
//               through, in RGB (albedo is applied by the composite).
// The sky is read at mip `sky_lod`: each sample then stands for a patch of
// sky rather than one texel of it, so a small bright sun does not turn into
// per-pixel sparkle (seed 003).
#include "include/ssdo.glsl"

void cavity_main(ivec2 pixel) {
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    if (isBackground(p.w) || lengthSquared(nrm) == 0.0) {
        // Background: fully open. Its radiance is the sky seen through the
        // pixel (level 0), so the composite has the sky to show there.
        vec3 ray = normalize(viewRayAt(pixel));
        write_visibility(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        write_radiance(pixel, vec4(textureLod(in_sky, skyUv(ray), 0.0).rgb, 1.0));
        return;
    }
    nrm = portableNormalize(nrm);
    SsdoBasis f = ssdoBasis(pixel, nrm);
    int n = clamp(P.samples, 1, 256);
    SkyGather g = SkyGather(0.0, 0.0, vec3(0.0));
    for (int i = 0; i < n; ++i) {
        SsdoSample s = ssdoSample(f, p.xyz, pixel, i, n, clamp(P.steps, 1, 16), P.radius, P.bias);
        gatherSky(g, nrm, s.dir, textureLod(in_sky, skyUv(s.dir), P.sky_lod).rgb, s.visible);
    }
    write_visibility(pixel, vec4(skyVisibility(g, P.contrast), 0.0, 0.0, 0.0));
    write_radiance(pixel, vec4(skyRadiance(g, n), 1.0));
}
