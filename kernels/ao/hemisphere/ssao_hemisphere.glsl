// Hemisphere-kernel SSAO (Crytek 2007 / Chapman 2013), as taught in
// the hemisphere SSAO lesson (docs/kernels.md), with positions reconstructed from hardware depth
// as in Chapman's SSAO tutorial: test n points inside the normal-oriented
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
        EXACT vec2 rotated = vec2(r.x * cs.x - r.y * cs.y, r.x * cs.y + r.y * cs.x);
        r = rotated;
    }
    // The noise vector, Gram-Schmidt against N: a random tangent (seed 004, step 4).
    vec3 t, b;
    tangentFrame(r, nrm, t, b);

    int n = clamp(P.samples, 1, 256);
    // Kernel points come in groups along one direction (P.kernel[i].w = 1
    // closes a group): a direction is blocked when any of its points is, as
    // a ray is blocked by the first thing it meets. Seed 004's kernel is all
    // groups of one point, which is its plain count of occluded points; the
    // hemisphere_cosine kernel (decl_screen_space.cpp) marches each
    // direction in steps out to R instead.
    // step_jitter (hemisphere_cosine): the steps of direction g move in by a
    // share u in [0, 1) of one step, drawn per pixel and direction, so that
    // an occluder thinner than a step (a plate 0.1R thick) is met by some
    // pixels' steps rather than by none; the box blur averages the rest.
    // Step j of a group lies at (j + 1) steps, so the move is a factor
    // 1 - u / (j + 1) on its length.
    float occlusion = 0.0, directions = 0.0, blocked = 0.0;
    int inGroup = 0;
    for (int i = 0; i < n; ++i) {
        vec4 k = P.kernel[i];
        EXACT float lengthScale = P.radius;
        if (P.step_jitter != 0)
            lengthScale = P.radius * (1.0 - sampleHash(pixel, int(directions)) * portableReciprocal(float(inGroup + 1)));
        EXACT vec3 s = p + (t * k.x + b * k.y + nrm * k.z) * lengthScale;
        float hit = 0.0;
        ivec2 texel;
        // A sample behind the camera plane has no depth to test against.
        if (texelOfView(s, texel)) {
            // As the seed's clamp-to-edge sampler: off-screen samples test
            // against the border texel.
            texel = clamp(texel, ivec2(0), frame.size - 1);
            vec3 q = viewFromDepth(texel, texelFetch(in_depth, texel, 0).r);
            // Is the sample behind the stored surface? q lies on the ray
            // through its texel's centre, up to half a texel beside the
            // sample, and on a plane seen at a grazing angle the depth changes
            // over that half texel by more than any sensible bias, so that
            // comparing depths makes the plane shadow itself (seed 004 tunes
            // bias against it; on `open` at 160x90 a quarter of the floor read
            // as occluded). The stored surface's plane (q and its normal) is
            // exact there: the camera sees the plane's front side, so "behind
            // the surface along the sample's ray" is "on the back side of the
            // plane", N_q . (s - q) < -bias, a test with no division that
            // holds at any angle, edge-on included. Where the texel's normal
            // faces away (a ray-marched silhouette) or is missing
            // (background), q's own depth stands.
            // A stored point below the receiver's tangent plane cannot be in
            // front of the sample (the camera and the sample are both above
            // that plane, and so is the segment between them); it shows up
            // only where the sample's ray and the texel's centre ray part
            // across an edge, a convex one most of all. Not an occluder.
            vec3 nq = texelFetch(in_normal, texel, 0).xyz;
            EXACT vec3 rise = q - p;
            bool occluded = false;
            if (orderedDot(nrm, rise) <= 0.0) {
                occluded = false;
            } else if (lengthSquared(nq) > 0.0 && orderedDot(nq, q) < 0.0) {
                nq = portableNormalize(nq);
                EXACT vec3 rel = s - q;
                occluded = orderedDot(nq, rel) < -P.bias;
            } else {
                // View z grows towards the camera: the stored surface hides
                // the sample when its z is larger, by at least `bias`.
                EXACT float threshold = s.z + P.bias;
                occluded = q.z >= threshold;
            }
            // Range check (seed 004): a surface much further than R in depth
            // (a far floor seen past a silhouette) must not occlude, or
            // silhouettes get dark halos. Kept on one line: the planted-bug
            // test deletes it.
            float rangeWeight = 1.0;
            if (P.range_check != 0) rangeWeight = smoothstep(0.0, 1.0, P.radius / max(abs(p.z - q.z), 1e-6));
            hit = (occluded ? 1.0 : 0.0) * rangeWeight;
        }
        blocked = max(blocked, hit);
        ++inGroup;
        if (k.w > 0.5 || i == n - 1) {
            occlusion += blocked;
            directions += 1.0;
            blocked = 0.0;
            inGroup = 0;
        }
    }
    float ao = max(1.0 - occlusion / directions, 0.0);
    // The power curve is pow(ao, contrast), not 002's
    // 1 - pow(1 - occluded/n, power): that expression is the complement (an
    // occlusion amount, 0 on an open plane), so read as AO it would turn
    // open surfaces black. pow(ao, k) keeps 1 = open for every k; it is 004's
    // exercise 4 and the same curve as Alchemy's contrast, hence the name.
    ao = pow(ao, P.contrast);
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
}
