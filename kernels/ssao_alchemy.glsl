// Alchemy screen-space ambient obscurance (McGuire et al. 2011), as
// 000_79d41de70034b569.txt gives it: n samples on a spiral in a screen disc
// whose radius is the world-space radius R seen at the fragment's depth;
// each sample's G-buffer position counts as an occluder in proportion to
// how far it rises above the fragment's tangent plane, with inverse-square
// falloff. Output: AO in [0, 1], 1 = fully open.
#include "include/common.glsl"
#include "include/noise.glsl"

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

    // h = alpha R / d in the seed is in units of the image plane at unit
    // distance; a pixel is 1 / f of that, with f = 0.5 H / tan(fovY / 2)
    // the focal length in pixels. So the disc radius of sample i is
    // h_px = alpha R f / d = (i + 0.5) * discScale, discScale = R f / (n d).
    // portableReciprocal keeps discScale identical on CPU and GPU, because
    // floor() below turns any difference into a different sample pixel.
    precise float focal = 0.5 * float(frame.size.y) * portableReciprocal(frame.camera.y);
    precise float discScale = R * focal * portableReciprocal(float(n) * d);
    // Per-pixel phase phi = 2 pi u of the spiral, so that neighbouring pixels
    // sample different offsets and the blur can average the pattern away.
    float u = pixelHash(pixel);
    vec2 fragCentre = vec2(pixel) + 0.5;

    float S = 0.0;
    for (int i = 0; i < n; ++i) {
        // theta = 2 pi alpha (7n/9) + phi; with alpha = (i + 0.5) / n the
        // angle in turns is (i + 0.5) 7/9 + u, whatever n is. 7/9 of a turn
        // per sample spreads successive samples evenly around the disc.
        precise float turns = (float(i) + 0.5) * 0.7777778 + u;
        vec2 dirCS = cosSinTurns(turns);
        precise float h = (float(i) + 0.5) * discScale;
        precise vec2 samplePos = fragCentre + dirCS * h;
        ivec2 s = ivec2(floor(samplePos));
        if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, frame.size))) continue;
        vec4 Pi = texelFetch(in_position, s, 0);
        if (isBackground(Pi.w)) continue;

        precise vec3 omega = Pi.xyz - X;
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
