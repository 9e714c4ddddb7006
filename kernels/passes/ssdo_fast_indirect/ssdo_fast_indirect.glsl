// ssdo_fast's one-bounce indirect light: ssdo_indirect.glsl's gather
// (Ritschel et al., I3D 2009, "The bounce - sender as emitter") over the
// points ssdo_fast_direct.glsl found blocked. The sender is rebuilt from the
// pyramid's depth on its own pixel's ray; its normal, blurred radiance and
// albedo are read at that pixel, once per blocked direction.
#include "include/ssdo_fast.glsl"

// The bounce over the receiver's blocked directions. Called with r.view,
// or with belowTiny(r.view) where every level is below the tiny ones (as
// ssdo_fast_direct.glsl does).
vec3 gatherBounce(FastReceiver r, ivec2 pixel) {
    vec3 gathered = vec3(0.0);
    for (int i = 0; i < r.count; ++i) {
        FastSample s = fastSample(r, pixel, i);
        if (s.visible) continue;
        vec3 m = texelFetch(in_normal, s.sender, 0).xyz;
        if (lengthSquared(m) == 0.0) continue;
        vec3 emitted = texelFetch(in_radiance, s.sender, 0).rgb * texelFetch(in_albedo, s.sender, 0).rgb;
        gathered += bounceFrom(r.X, r.n, positionAt(s.sender, s.senderDepth), normalize(m), emitted, P.radius,
                               P.distance_clamp);
    }
    return gathered;
}

void cavity_main(ivec2 pixel) {
    FastReceiver r;
    if (!fastReceiver(pixel, r)) {
        write_indirect(pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    vec3 gathered;
    if (r.view.maxLevel < r.view.tiny) {
        r.view = belowTiny(r.view);
        gathered = gatherBounce(r, pixel);
    } else {
        gathered = gatherBounce(r, pixel);
    }
    float area = PI * P.radius * P.radius / float(r.count);
    write_indirect(pixel, vec4(gathered * (area * P.bounce_strength / PI), 1.0));
}
