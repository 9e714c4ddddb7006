// GTAO (Jimenez, Wu, Pesce, Jarabo 2016). The hemisphere around the view
// vector V is cut into `slices` planes that contain V, each rotated per
// pixel. In each slice the horizon on either side is the highest elevation,
// seen from the pixel, of the G-buffer surface within the radius R; the
// visibility of the slice is the cosine-weighted integral between the two
// horizons, around the normal projected into the slice, which has a closed
// form. The slices' mean is the visibility: 1 = fully open.
#include "include/common.glsl"
#include "include/noise.glsl"
#include "include/octahedral.glsl"

// The integral of cos(h - n) |sin h| over [0, h] in closed form, one side of
// a slice (Jimenez et al. 2016, eq. 7): 0.25 (-cos(2h - n) + cos n + 2 h sin n).
float sideIntegral(float h, float n) {
    return 0.25 * (-cos(2.0 * h - n) + cos(n) + 2.0 * h * sin(n));
}

// The multi-bounce fit (eq. 10): visibility raised by the light the albedo
// bounces, a cubic in the visibility whose coefficients are linear in it.
float multiBounce(float v, float albedo) {
    float a = 2.0404 * albedo - 0.3324;
    float b = -4.7951 * albedo + 0.6417;
    float c = 2.7552 * albedo + 0.6903;
    return max(v, ((v * a + b) * v + c) * v);
}

// The highest horizon cosine on one side of the slice: `dir` in pixels, the
// search starting one pixel out and reaching rPx pixels in `steps` steps.
float horizonCos(vec3 X, vec3 V, vec2 centre, vec2 dir, float rPx, int steps, float jitter, float lowest) {
    float best = lowest;
    float R2 = P.radius * P.radius;
    float stride = max(rPx - 1.0, 0.0) / float(steps);
    for (int k = 0; k < steps; ++k) {
        ivec2 s = ivec2(floor(centre + dir * (1.0 + (float(k) + jitter) * stride)));
        if (!inImage(s)) continue;
        vec4 S = texelFetch(in_position, s, 0);
        if (isBackground(S.w)) continue;
        vec3 d = S.xyz - X;
        float d2 = lengthSquared(d);
        // Occluders beyond R do not count, as the ground truth's rays end at R.
        if (d2 > R2 || d2 <= 0.0) continue;
        best = max(best, dot(d, V) * inversesqrt(d2));
    }
    return best;
}

void cavity_main(ivec2 pixel) {
    vec4 centre = texelFetch(in_position, pixel, 0);
    float depth = centre.w;
    if (isBackground(depth)) {
        write_ao(pixel, vec4(1.0));
        write_ao_key(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    vec3 X = centre.xyz;
    vec3 N = normalize(texelFetch(in_normal, pixel, 0).xyz);
    vec3 V = normalize(-X);

    int slices = P.slices;
    int steps = max(1, P.samples / (2 * slices));
    // R seen at this depth, in pixels: focal length in pixels times R / depth.
    float focal = 0.5 * float(frame.size.y) / frame.camera.y;
    float rPx = P.radius * focal / depth;
    vec2 centrePx = vec2(pixel) + 0.5;
    float rotation = samplePhase(pixel);
    float jitter = ign(centrePx);

    float visibility = 0.0;
    for (int i = 0; i < slices; ++i) {
        vec2 cs = cosSinTurns((float(i) + rotation) * 0.5 / float(slices));
        // The slice's direction on screen (y down) and in view space (y up).
        vec3 direction = vec3(cs.x, -cs.y, 0.0);
        vec3 ortho = direction - dot(direction, V) * V;
        vec3 axis = normalize(cross(ortho, V));
        vec3 projected = N - axis * dot(N, axis);
        float projectedLength = length(projected);
        if (projectedLength < 1e-6) continue;
        float cosN = clamp(dot(projected, V) / projectedLength, -1.0, 1.0);
        float n = sign(dot(ortho, projected)) * acos(cosN);
        // The lowest horizons: the tangent plane in the slice.
        float c1 = horizonCos(X, V, centrePx, cs, rPx, steps, jitter, cos(n + 0.5 * PI));
        float c2 = horizonCos(X, V, centrePx, -cs, rPx, steps, jitter, cos(n - 0.5 * PI));
        float h1 = acos(clamp(c1, -1.0, 1.0));
        float h2 = -acos(clamp(c2, -1.0, 1.0));
        h1 = n + min(h1 - n, 0.5 * PI);
        h2 = n + max(h2 - n, -0.5 * PI);
        visibility += projectedLength * (sideIntegral(h1, n) + sideIntegral(h2, n));
    }
    visibility = clamp(visibility / float(slices), 0.0, 1.0);
    if (P.multibounce != 0) {
        // The albedo image stays at full resolution when the AO runs at half.
        ivec2 scale = max(textureSize(in_albedo, 0) / frame.size, ivec2(1));
        vec3 albedo = texelFetch(in_albedo, pixel * scale, 0).rgb;
        visibility = multiBounce(visibility, dot(albedo, vec3(1.0 / 3.0)));
    }
    write_ao(pixel, vec4(visibility, 0.0, 0.0, 0.0));
    write_ao_key(pixel, vec4(visibility, depth, octEncode(N)));
}
