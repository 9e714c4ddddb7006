// The sampling both SSDO families share (Ritschel et al., I3D 2009): the
// per-pixel basis and the n hemisphere directions, the sky gathered by the
// direct passes, and the bounce a sender sends the receiver. Reads no image:
// ssdo.glsl tests visibility on the G-buffer, ssdo_fast.glsl on the depth
// pyramid.
#include "include/screen_space.glsl"
#include "include/sky.glsl"

struct SsdoBasis {
    vec3 t, b, n;
    float phiTurns;   // the seed's phi, in turns
};

// Tangent frame from an auxiliary up vector never collinear with N (seed
// 003), and the per-pixel azimuth offset phi = pi IGN, i.e. IGN / 2 turns.
SsdoBasis ssdoBasis(ivec2 pixel, vec3 n) {
    SsdoBasis f;
    vec3 up = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    f.n = n;
    f.t = portableNormalize(orderedCross(up, n));
    f.b = orderedCross(n, f.t);
    f.phiTurns = 0.5 * ign(vec2(pixel) + 0.5);
    return f;
}

// Direction i of `count`: stratified elevation cos = 1 - alpha with
// alpha = (i + 0.5) / count, uniform in solid angle over the hemisphere (so
// each sample stands for 2 pi / count steradians), and azimuth
// 2 pi alpha (7 count / 9) + phi, which is (i + 0.5) 7/9 turns + phi
// whatever the count: successive samples 7/9 of a turn apart.
// T, B, N are orthonormal and the local vector is unit, so the seed's
// final normalize would change only rounding; it is left out.
vec3 ssdoDirection(SsdoBasis f, int i, int count) {
    EXACT float alpha = (float(i) + 0.5) * portableReciprocal(float(count));
    EXACT float cosE = 1.0 - alpha;
    EXACT float sin2 = 1.0 - cosE * cosE;
    EXACT float sinE = sin2 * portableInverseSqrt(sin2);
    EXACT float turns = (float(i) + 0.5) * 0.7777778 + f.phiTurns;
    vec2 cs = cosSinTurns(turns);
    EXACT vec3 d = f.t * (sinE * cs.x) + f.b * (sinE * cs.y) + f.n * cosE;
    return d;
}

// What a direct pass gathers over the directions: the sky's luminance-
// weighted energy that reaches the receiver against all of it (visibility),
// and the radiance of the open directions.
struct SkyGather {
    float total, visible;
    vec3 direct;
};

// Direction `dir` of the receiver with normal `n`, whose sky radiance is
// `sky`, found open or not.
void gatherSky(inout SkyGather g, vec3 n, vec3 dir, vec3 sky, bool open) {
    float cosTheta = max(orderedDot(n, dir), 0.0);
    float weight = skyLuminance(sky) * cosTheta;
    g.total += weight;
    if (open) {
        g.visible += weight;
        g.direct += sky * cosTheta;
    }
}

// The direct pass's two results from `count` directions: visibility shaped
// by `contrast`, and L_dir = sum (1/pi) L_in cos(theta) (2 pi / n), the
// constant factors (1/pi)(2 pi / n) = 2 / n applied once.
float skyVisibility(SkyGather g, float contrast) {
    float visibility = g.total > 0.0 ? g.visible / g.total : 1.0;
    return clamp(pow(visibility, contrast), 0.0, 1.0);
}

vec3 skyRadiance(SkyGather g, int count) {
    return g.direct * (2.0 / float(count));
}

// The light a sender patch at q (unit normal m, emitting `emitted`, its
// blurred direct radiance times its albedo) sends the receiver at p with
// unit normal n, before the constant area and strength factors:
//     cos(theta_s) cos(theta_r) falloff / d^2
// theta_s between m and the way to the receiver, theta_r between n and the
// way to the sender, falloff = max(0, 1 - dist / R) fading senders out at
// the hemisphere's edge, d = max(distance_clamp, dist) bounding 1/d^2 where
// the two nearly touch. The seed's listing takes both cosines with the sign
// opposite to its own definitions (it would bleed light only from surfaces
// facing away); the definitions are what is implemented.
vec3 bounceFrom(vec3 p, vec3 n, vec3 q, vec3 m, vec3 emitted, float radius, float distanceClamp) {
    vec3 toSender = q - p;
    float dist = length(toSender);
    if (dist <= 0.0) return vec3(0.0);
    vec3 w = toSender / dist;
    float cosSender = max(dot(m, -w), 0.0);
    float cosReceiver = max(dot(n, w), 0.0);
    float falloff = max(1.0 - dist / radius, 0.0);
    float d = max(distanceClamp, dist);
    return emitted * (cosSender * cosReceiver * falloff / (d * d));
}
