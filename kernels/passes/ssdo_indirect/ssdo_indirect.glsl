// SSDO one-bounce indirect light (Ritschel et al., I3D 2009, "The bounce -
// sender as emitter"). The samples the direct pass found occluded hit a
// surface that is itself lit. Each is taken as a small Lambertian patch of
// area A_s = pi R^2 / n re-emitting its blurred direct radiance times its
// albedo, and the receiver gathers
//
//     L_ind = sum (1/pi) L_s rho_s A_s cos(theta_s) cos(theta_r) strength falloff / d^2
//
// (include/ssdo_sampling.glsl's bounceFrom has the terms).
//
// Inputs: position, normal, albedo (G-buffer) and radiance, the blurred
// direct radiance: pre-blurring keeps one noisy sender from spiking the
// bounce (seed 003).
#include "include/ssdo.glsl"

void cavity_main(ivec2 pixel) {
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    if (isBackground(p.w) || lengthSquared(nrm) == 0.0) {
        write_indirect(pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    nrm = portableNormalize(nrm);
    SsdoBasis f = ssdoBasis(pixel, nrm);
    int n = clamp(P.samples, 1, 256);
    vec3 gathered = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        SsdoSample s = ssdoSample(f, p.xyz, pixel, i, n, clamp(P.steps, 1, 16), P.radius, P.bias);
        if (s.visible) continue;
        vec3 q = texelFetch(in_position, s.texel, 0).xyz;
        vec3 m = normalize(texelFetch(in_normal, s.texel, 0).xyz);
        vec3 emitted = texelFetch(in_radiance, s.texel, 0).rgb * texelFetch(in_albedo, s.texel, 0).rgb;
        gathered += bounceFrom(p.xyz, nrm, q, m, emitted, P.radius, P.distance_clamp);
    }
    float area = PI * P.radius * P.radius / float(n);
    write_indirect(pixel, vec4(gathered * (area * P.bounce_strength / PI), 1.0));
}
