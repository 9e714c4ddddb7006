// Alchemy screen-space ambient obscurance (McGuire et al. 2011), as
// McGuire et al., HPG 2011 gives it: n samples on a spiral in a screen disc
// whose radius is the world-space radius R seen at the fragment's depth;
// each sample's G-buffer position counts as an occluder in proportion to
// how far it rises above the fragment's tangent plane, with inverse-square
// falloff. Output: AO in [0, 1], 1 = fully open.
#include "include/common.glsl"
#include "include/noise.glsl"
#include "include/alchemy_spiral.glsl"

void cavity_main(ivec2 pixel) {
    vec4 centre = texelFetch(in_position, pixel, 0);
    float d = centre.w;
    if (isBackground(d)) {
        write_ao(pixel, vec4(1.0));
        return;
    }
    vec3 X = centre.xyz;   // the seed's P (P is the parameter block here)
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;

    int n = P.samples;
    float R = P.radius;
    // c = 0.1 R caps the inverse-square falloff: a sample right next to the
    // fragment would otherwise weigh without bound (1 / |w|^2 -> infinity).
    float c = 0.1 * R;
    float weight = 2.0 * PI * c / float(n);

    float discScale = spiralDiscScale(R, n, d);
    // Per-pixel phase phi = 2 pi u of the spiral, so that neighbouring pixels
    // sample different offsets and the blur can average the pattern away.
    float u = pixelHash(pixel);
    vec2 fragCentre = vec2(pixel) + 0.5;

    float S = 0.0;
    for (int i = 0; i < n; ++i) {
        float h;
        ivec2 s = spiralSample(i, u, discScale, fragCentre, h);
        if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, frame.size))) continue;
        vec4 Pi = texelFetch(in_position, s, 0);
        if (isBackground(Pi.w)) continue;

        EXACT vec3 omega = Pi.xyz - X;
        float omega2 = lengthSquared(omega);
        // H = step(0, R - |w|), compared squared: no sqrt, so the test
        // cannot come out differently on the CPU at |w| = R.
        if (omega2 > R * R) continue;
        // The bias keeps samples on the fragment's own plane, lifted only
        // by G-buffer rounding, from reading as occluders.
        S += weight * max(0.0, dot(N, omega) - P.bias) / max(c * c, omega2);
    }
    float A = pow(max(0.0, 1.0 - P.scale * S), P.contrast);
    write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));
}
