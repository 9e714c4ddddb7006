// Hemisphere-kernel SSAO (Crytek 2007 / Chapman 2013), as taught in
// 004_94976db8e6612027.txt, with positions reconstructed from hardware depth
// as in 002_fea56af43bca7c1b.txt: test n points inside the normal-oriented
// hemisphere of radius R against the depth buffer. Output: AO in [0, 1],
// 1 = open.
//
// Inputs: in_depth (hardware depth from depth_from_position, 1 = nothing),
// in_normal (view normal), in_noise4x4 (the 4x4 rotation tile).
// P.kernel[i].xyz is tangent-space sample i of an n-sample kernel, made on
// the CPU (decl_screen_space.cpp) because it depends on n only.
#include "include/screen_space.glsl"

void cavity_main(ivec2 pixel) {
    float depth = texelFetch(in_depth, pixel, 0).r;
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    // Background: nothing to occlude.
    if (depth >= 1.0 || lengthSquared(nrm) == 0.0) {
        write_ao(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    nrm = portableNormalize(nrm);
    vec3 p = viewFromDepth(pixel, depth);

    // texelFetch ignores the sampler's REPEAT, so the tile wraps here.
    vec2 r = texelFetch(in_noise4x4, pixel & 3, 0).xy;
    if (P.ign_jitter != 0) {
        // A per-pixel rotation by IGN on top of the tile makes each pixel's
        // kernel orientation nearly unique, hiding the 4-pixel grid (seed
        // 004, "IGN jitter"). cosSinTurns: GLSL's cos/sin are too loose.
        vec2 cs = cosSinTurns(ign(vec2(pixel) + 0.5));
        precise vec2 rotated = vec2(r.x * cs.x - r.y * cs.y, r.x * cs.y + r.y * cs.x);
        r = rotated;
    }
    // Gram-Schmidt (seed 004, step 4): the noise vector minus its component
    // along N is a random tangent. It vanishes only when N lies in the view
    // xy plane along the noise vector; the perpendicular in xy is then a
    // tangent instead.
    vec3 rv = vec3(r, 0.0);
    precise vec3 t = rv - nrm * orderedDot(rv, nrm);
    if (lengthSquared(t) < 1e-6) {
        rv = vec3(-r.y, r.x, 0.0);
        t = rv - nrm * orderedDot(rv, nrm);
    }
    t = portableNormalize(t);
    vec3 b = orderedCross(nrm, t);

    int n = clamp(P.samples, 1, 256);
    float occlusion = 0.0;
    for (int i = 0; i < n; ++i) {
        vec3 k = P.kernel[i].xyz;
        precise vec3 s = p + (t * k.x + b * k.y + nrm * k.z) * P.radius;
        ivec2 texel;
        // A sample behind the camera plane has no depth to test against.
        if (!texelOfView(s, texel)) continue;
        // As the seed's clamp-to-edge sampler: off-screen samples test
        // against the border texel.
        texel = clamp(texel, ivec2(0), frame.size - 1);
        vec3 q = viewFromDepth(texel, texelFetch(in_depth, texel, 0).r);
        // The stored surface's depth along the sample's own ray. q lies on
        // the ray through its texel's centre, up to half a texel beside the
        // sample; on a plane seen at a grazing angle the depth changes by
        // more than any sensible bias over that half texel, and the plane
        // shadows itself (seed 004 tunes bias against it; on `open` at
        // 160x90 a quarter of the floor read as occluded). So intersect the
        // sample's ray (through the eye, view-space origin) with the plane
        // of q and the texel's normal: z = s.z (Nq . q) / (Nq . s), exact on
        // a plane and never mixing surfaces across a silhouette. Where that
        // plane is seen nearly edge-on (|cos| under 0.01) or faces away, or
        // the texel is background (normal 0), q's own depth stands.
        vec3 nq = texelFetch(in_normal, texel, 0).xyz;
        precise float ns = orderedDot(nq, s);
        precise float edgeOn = 1e-4 * lengthSquared(nq) * lengthSquared(s);
        precise float stored = q.z;
        if (ns < 0.0 && ns * ns > edgeOn) {
            precise float along = -orderedDot(nq, q) * portableReciprocal(-ns);
            stored = along * s.z;
        }
        // Range check (seed 004): a surface much further than R in depth
        // (a far floor seen past a silhouette) must not occlude, or
        // silhouettes get dark halos. Kept on one line: the planted-bug
        // test deletes it.
        float rangeWeight = 1.0;
        if (P.range_check != 0) rangeWeight = smoothstep(0.0, 1.0, P.radius / max(abs(p.z - q.z), 1e-6));
        // View z grows towards the camera: the stored surface hides the
        // sample when its z is larger, by at least `bias` (G-buffer and
        // depth rounding).
        precise float threshold = s.z + P.bias;
        occlusion += (stored >= threshold ? 1.0 : 0.0) * rangeWeight;
    }
    float ao = max(1.0 - occlusion / float(n), 0.0);
    // The power curve is pow(ao, contrast), not 002's
    // 1 - pow(1 - occluded/n, power): that expression is the complement (an
    // occlusion amount, 0 on an open plane), so read as AO it would turn
    // open surfaces black. pow(ao, k) keeps 1 = open for every k; it is 004's
    // exercise 4 and the same curve as Alchemy's contrast, hence the name.
    ao = pow(ao, P.contrast);
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
}
