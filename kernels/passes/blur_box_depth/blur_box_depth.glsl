// Seed 004's 4x4 box blur (blur_box.glsl) kept to one surface: a texel of
// the window counts only when it and the centre lie within 0.1 R of each
// other's tangent planes. Seed 004's box ignores depth, so at a silhouette
// it averages the AO of the object in front with that of the wall behind:
// the sphere's contact darkening spreads over the wall texels beside its
// outline, a grey ring round it. The box stays a box (equal
// weights, the same window) so that, away from edges, one whole period of
// the 4x4 rotation tile is still averaged and the tile cancels; at an edge
// the window holds part of a period and some of the tile's pattern stays,
// a texel or two wide.
//
// Why both planes: at a silhouette the centre's own tangent plane contains
// the view ray, so the wall behind it lies close to that plane; the wall's
// plane is far from the silhouette point. Taking the larger of the two
// distances rejects the pair from either side. Why 0.1 R: AO is the
// visibility within R, so two points much closer than R to each other's
// planes see nearly the same occluders; a plane's own texels lie at
// distance 0 (up to depth rounding, 1e-5 of the depth here), and a curved
// surface's neighbours at d^2 / (2 r) for a texel spacing d, far under it.
//
// Inputs: ao (the hemisphere kernel's raw AO), depth (hardware depth, as
// the hemisphere kernel reads it), normal; all at the AO's resolution.
#include "include/screen_space.glsl"

void cavity_main(ivec2 pixel) {
    ivec2 size = textureSize(in_ao, 0);
    float depth = texelFetch(in_depth, pixel, 0).r;
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    if (depth >= 1.0 || lengthSquared(nrm) == 0.0) {
        write_ao(pixel, vec4(texelFetch(in_ao, pixel, 0).r, 0.0, 0.0, 0.0));
        return;
    }
    nrm = portableNormalize(nrm);
    vec3 p = viewFromDepth(pixel, depth);
    EXACT float tolerance = 0.1 * P.radius;
    // The same window as blur_box.glsl: it slides inwards at the border.
    ivec2 start = clamp(pixel - 2, ivec2(0), max(size - 4, ivec2(0)));
    float sum = 0.0, count = 0.0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            ivec2 t = min(start + ivec2(x, y), size - 1);
            float dt = texelFetch(in_depth, t, 0).r;
            vec3 nt = texelFetch(in_normal, t, 0).xyz;
            if (dt >= 1.0 || lengthSquared(nt) == 0.0) continue;
            nt = portableNormalize(nt);
            EXACT vec3 q = viewFromDepth(t, dt);
            EXACT vec3 qp = q - p;
            EXACT float fromCentre = abs(orderedDot(nrm, qp));
            EXACT float fromTap = abs(orderedDot(nt, qp));
            if (max(fromCentre, fromTap) > tolerance) continue;
            sum += texelFetch(in_ao, t, 0).r;
            count += 1.0;
        }
    // The centre always counts (distance 0), so count >= 1.
    write_ao(pixel, vec4(sum / count, 0.0, 0.0, 0.0));
}
