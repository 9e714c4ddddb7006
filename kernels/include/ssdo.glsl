// The hemisphere sampling shared by the SSDO direct and indirect passes
// (Ritschel et al., I3D 2009): both must walk the very same directions,
// lengths and visibility verdicts, since the indirect pass re-uses the
// occluded samples of the direct one as senders.
//
// A kernel including this file declares inputs named `position` and
// `normal` (the G-buffer at the output's resolution).
#include "include/ssdo_sampling.glsl"

struct SsdoSample {
    vec3 dir;
    bool visible;
    ivec2 texel;   // where the sample projects: the sender when not visible
};

// Whether a point in the receiver's hemisphere lies behind what the
// G-buffer records (seed 003's screen-space visibility test), and the texel
// it projects to: the sender when it does.
//
// Open (seed 003) when it projects outside the image, onto background
// (normal 0), or when it is no further from the camera than the recorded
// surface. That distance is taken along the point's own ray, through the
// recorded surface's tangent plane: the recorded point lies on its texel's
// centre ray, up to half a texel beside the point's, and comparing the raw
// distances lets an open plane occlude itself wherever its depth changes
// across a texel (everywhere off the image centre). The camera is in front
// of any surface it sees, so "no further along the ray than the plane" is
// "on the plane's front side": N_s . (S - Q) >= -bias, with the same bias
// against G-buffer rounding as the other kernels. A recorded normal facing
// away from the camera (possible at ray-marched silhouettes) falls back to
// the plain distance test.
bool ssdoBlocked(SsdoBasis f, vec3 p, vec3 point, float bias, out ivec2 texel) {
    if (!texelOfView(point, texel) || !texelInside(texel)) return false;
    vec4 q = texelFetch(in_position, texel, 0);
    vec3 m = texelFetch(in_normal, texel, 0).xyz;
    if (isBackground(q.w) || lengthSquared(m) == 0.0) return false;
    // The camera and the sample both lie above the receiver's tangent plane
    // (it sees the receiver; the sample is in its hemisphere), so everything
    // on the segment between them does too: a recorded point below that
    // plane is not in front of the sample. It still turns up where the
    // sample's ray and its texel's centre ray part across an edge, a convex
    // edge most of all (the texel shows the far face, whose plane the sample
    // is behind): 0.972 on an open convex corner at 160x90. Not an occluder.
    EXACT vec3 rise = q.xyz - p;
    if (orderedDot(f.n, rise) <= 0.0) return false;
    if (orderedDot(m, q.xyz) < 0.0) {
        EXACT vec3 rel = point - q.xyz;
        return orderedDot(m, rel) < -bias;
    }
    EXACT float reach = lengthSquared(q.xyz);
    EXACT float limit = reach * portableInverseSqrt(reach) + bias;
    return lengthSquared(point) > limit * limit;
}

// Direction i at p (view space), tested at `steps` points along it.
//
// steps = 1 is seed 003's sampling: one point at a length lambda in (0, R]
// drawn per pixel and direction (it jitters the shells into noise that the
// bilateral blur removes). That point finds a wall the direction meets at
// distance t only when lambda > t, with probability (R - t) / R, so at a
// 90 degree crease the seed reads 0.88 where the cosine-weighted visibility
// within R is 0.58. With steps = k the direction is marched
// instead, as hemisphere_cosine marches its rays: point j at
// (j + 1 - u) R / k for the same per-pixel u in [0, 1), each moved in by a
// share of one step, so a solid occluder met within R is found unless it
// lies in the last step's reach, and one thinner than a step by some
// pixels' steps. The direction is blocked by its first blocked point, whose
// texel is the sender the bounce reads (the first surface the ray meets).
// k = 1 gives the seed's lambda = R (1 - u) bit for bit.
SsdoSample ssdoSample(SsdoBasis f, vec3 p, ivec2 pixel, int i, int count, int steps, float radius, float bias) {
    SsdoSample s;
    s.dir = ssdoDirection(f, i, count);
    s.visible = true;
    s.texel = ivec2(-1);
    float u = sampleHash(pixel, i);
    EXACT float perStep = portableReciprocal(float(steps));
    for (int j = 0; j < steps; ++j) {
        EXACT float lambda = radius * ((float(j + 1) - u) * perStep);
        EXACT vec3 point = p + s.dir * lambda;
        ivec2 texel;
        if (ssdoBlocked(f, p, point, bias, texel)) {
            s.visible = false;
            s.texel = texel;
            return s;
        }
    }
    return s;
}
