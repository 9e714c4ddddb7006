// References of ssdo_indirect.glsl and ssdo_fast_indirect.glsl: one bounce
// of the blurred direct radiance from the senders the direct pass's samples
// are blocked by (ref_ssdo.cpp says how closely the GPU follows).
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/pyramid.h"
#include "reference/refs.h"
#include "reference/ssdo.h"
#include "reference/vec.h"

#include <algorithm>
#include <cmath>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
Vec3 normalizeExact(Vec3 v);
Vec3 texel3(const HostImage& img, int x, int y);
}  // namespace screen

using ssdo::Basis;
using ssdo::FastMarch;
using ssdo::Sample;
using ssdo::bounceFrom;
using ssdo::put;
using ssdo::ssdoBasis;
using ssdo::ssdoSample;

Result<std::vector<HostImage>> ssdoIndirect(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {4, 3, 3, 3}));
    const HostImage& position = *ctx.inputs[0];
    const HostImage& normal = *ctx.inputs[1];
    const HostImage& albedo = *ctx.inputs[2];
    const HostImage& radiance = *ctx.inputs[3];
    const auto& f = ctx.frame;
    const int n = std::clamp(intParam(ctx, "samples"), 1, 256);
    const float radius = floatParam(ctx, "radius"), bias = floatParam(ctx, "bias");
    const float strength = floatParam(ctx, "bounce_strength"), distanceClamp = floatParam(ctx, "distance_clamp");
    const int steps = std::clamp(intParam(ctx, "steps"), 1, 16);

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            Vec3 nrm = screen::texel3(normal, x, y);
            if (isBackground(position.at(x, y, 3)) || lengthSquared(nrm) == 0.0f) {
                put(out[0], x, y, {}, 1.0f);
                continue;
            }
            nrm = screen::normalizeExact(nrm);
            const Vec3 p = screen::texel3(position, x, y);
            const Basis basis = ssdoBasis(x, y, nrm);
            Vec3 gathered;
            for (int i = 0; i < n; ++i) {
                const Sample s = ssdoSample(f, position, normal, basis, p, x, y, i, n, steps, radius, bias);
                if (s.visible) continue;
                const Vec3 q = screen::texel3(position, s.tx, s.ty);
                const Vec3 m = normalize(screen::texel3(normal, s.tx, s.ty));
                const Vec3 emitted = screen::texel3(radiance, s.tx, s.ty) * screen::texel3(albedo, s.tx, s.ty);
                gathered = gathered + bounceFrom(p, nrm, q, m, emitted, radius, distanceClamp);
            }
            const float area = kPi * radius * radius / float(n);
            put(out[0], x, y, gathered * (area * strength / kPi), 1.0f);
        }
    return out;
}

// ssdo_fast_indirect.glsl: inputs the pyramid's level 0, normal, albedo and
// the blurred radiance.
Result<std::vector<HostImage>> ssdoFastIndirect(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 3, 3, 3}));
    const HostImage& albedo = *ctx.inputs[2];
    const HostImage& radiance = *ctx.inputs[3];
    const auto& f = ctx.frame;
    const FastMarch march(ctx);
    const float strength = floatParam(ctx, "bounce_strength"), distanceClamp = floatParam(ctx, "distance_clamp");

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            FastMarch::Receiver r;
            if (!march.receiver(x, y, r)) {
                put(out[0], x, y, {}, 1.0f);
                continue;
            }
            Vec3 gathered;
            for (int i = 0; i < march.n; ++i) {
                float senderDepth = 0.0f;
                const Sample s = march.sample(r, x, y, i, senderDepth);
                if (s.visible) continue;
                const Vec3 m = screen::texel3(march.normal, s.tx, s.ty);
                if (lengthSquared(m) == 0.0f) continue;
                const Vec3 emitted = screen::texel3(radiance, s.tx, s.ty) * screen::texel3(albedo, s.tx, s.ty);
                gathered = gathered + bounceFrom(r.X, r.n, pyramid::positionAt(f, s.tx, s.ty, senderDepth), normalize(m),
                                                 emitted, march.radius, distanceClamp);
            }
            const float area = kPi * march.radius * march.radius / float(march.n);
            put(out[0], x, y, gathered * (area * strength / kPi), 1.0f);
        }
    return out;
}

}  // namespace cavity::reference
