// References of the SSDO kernels (Ritschel et al., I3D 2009): ssdo_direct.glsl,
// blur_bilateral_ssdo.glsl, ssdo_indirect.glsl and composite_ssdo.glsl, and
// of ssdo_fast's. This file holds the direct passes, the blur and the
// composite; ref_ssdo_indirect.cpp the bounce passes; ref_ssdo_sampling.cpp
// the sampling and the sky they share (reference/ssdo.h).
//
// Sample directions, lengths, texels, visibility verdicts and the sky
// coordinates are computed with the kernels' exact operations
// (include/ssdo.glsl, include/sky.glsl's portableAtan2), so both sides agree
// on which samples are open and where each reads the sky. The sky read
// itself is textureLod with linear filtering, mirrored here: bilinear within
// a level (texel centres at (i + 0.5) / size, indices clamped to the edge),
// linear between the two levels around `sky_lod`. That is the one part the
// GPU may round differently: Vulkan promises only 4 bits of subtexel and of
// mip-blend precision (lavapipe reports 8 and 4, desktop GPUs 8 and 8).
//
// Measured on lavapipe and llvmpipe (corner and slats, 161x91 and 320x180,
// 16-256 samples, sky_lod 2.3-6, compute and fragment): before the 16-bit
// store, visibility, radiance and indirect agree to 1e-6 relative (lavapipe
// filters in float). After it, to one half-float step: 4.9e-4 below 1,
// 9.8e-4 in [1, 2), 2^-11 relative above; so compare radiance and indirect
// with |a - b| <= 1e-3 max(1, |b|), not a flat 1e-3. Expected on GPUs that
// quantise filter weights to 8 bits (not measured): radiance within about
// 1/512 of the difference between neighbouring sky texels (at level 5,
// under 5e-3 relative next to the sun); visibility, a ratio of sums of the same
// weights, within 1e-3.
//
// The sky's levels come from the constant image's own generator, since a
// pass chain's read-back of the constant sky returns level 0 only.
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
Status requireInput(const Context& ctx, size_t i, int width, int height, int minChannels);
}  // namespace screen

using ssdo::Basis;
using ssdo::FastMarch;
using ssdo::Levels;
using ssdo::Sample;
using ssdo::SkyGather;
using ssdo::put;
using ssdo::sampleSky;
using ssdo::skyAmbient;
using ssdo::skyLevels;
using ssdo::skyUv;
using ssdo::ssdoBasis;
using ssdo::ssdoSample;
using ssdo::viewRay;

Result<std::vector<HostImage>> ssdoDirect(const Context& ctx) {
    const auto& f = ctx.frame;
    CAVITY_TRY(screen::requireInput(ctx, 0, f.size[0], f.size[1], 4));
    CAVITY_TRY(screen::requireInput(ctx, 1, f.size[0], f.size[1], 3));
    const Levels* sky = skyLevels();
    if (!sky) return internal("reference ssdo: no constant image 'sky' in screenSpaceConstants()");
    const HostImage& position = *ctx.inputs[0];
    const HostImage& normal = *ctx.inputs[1];
    const int n = std::clamp(intParam(ctx, "samples"), 1, 256);
    const float radius = floatParam(ctx, "radius"), bias = floatParam(ctx, "bias");
    const float contrast = floatParam(ctx, "contrast"), lod = floatParam(ctx, "sky_lod");
    const int steps = std::clamp(intParam(ctx, "steps"), 1, 16);

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            Vec3 nrm = screen::texel3(normal, x, y);
            if (isBackground(position.at(x, y, 3)) || lengthSquared(nrm) == 0.0f) {
                out[0].at(x, y) = 1.0f;
                put(out[1], x, y, sampleSky(*sky, skyUv(normalize(viewRay(f, x, y))), 0.0f), 1.0f);
                continue;
            }
            nrm = screen::normalizeExact(nrm);
            const Vec3 p = screen::texel3(position, x, y);
            const Basis basis = ssdoBasis(x, y, nrm);
            SkyGather g;
            for (int i = 0; i < n; ++i) {
                const Sample s = ssdoSample(f, position, normal, basis, p, x, y, i, n, steps, radius, bias);
                g.add(nrm, s.dir, sampleSky(*sky, skyUv(s.dir), lod), s.visible);
            }
            out[0].at(x, y) = g.visibility(contrast);
            put(out[1], x, y, g.radiance(n), 1.0f);
        }
    return out;
}

Result<std::vector<HostImage>> blurBilateralSsdo(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 3, 4, 3}));
    const HostImage& visIn = *ctx.inputs[0];
    const HostImage& radIn = *ctx.inputs[1];
    const HostImage& position = *ctx.inputs[2];
    const HostImage& normal = *ctx.inputs[3];
    const auto& f = ctx.frame;
    const int r = intParam(ctx, "blur");
    const float sigma = floatParam(ctx, "depth_sigma");
    const float twoSigma2 = 2.0f * sigma * sigma;
    const std::vector<float>& w = array(ctx, "weights");
    if (r > 0 && int(w.size()) <= r)
        return internal("reference blur_bilateral_ssdo: " + std::to_string(w.size()) + " weights for radius " +
                        std::to_string(r));

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            const float centreVis = visIn.at(x, y);
            const Vec3 centreRad = screen::texel3(radIn, x, y);
            const float d = position.at(x, y, 3);
            if (r == 0 || isBackground(d)) {
                out[0].at(x, y) = centreVis;
                put(out[1], x, y, centreRad, 1.0f);
                continue;
            }
            const Vec3 N = screen::texel3(normal, x, y);
            float visSum = 0.0f, total = 0.0f;
            Vec3 radSum;
            for (int ty = -r; ty <= r; ++ty)
                for (int tx = -r; tx <= r; ++tx) {
                    const int qx = x + tx, qy = y + ty;
                    if (qx < 0 || qy < 0 || qx >= f.size[0] || qy >= f.size[1]) continue;
                    const float di = position.at(qx, qy, 3);
                    if (isBackground(di)) continue;
                    const float spatial = w[size_t(std::abs(tx))] * w[size_t(std::abs(ty))];
                    const float normalWeight = std::max(0.0f, dot(N, screen::texel3(normal, qx, qy)));
                    const float depthWeight = std::exp(-(d - di) * (d - di) / twoSigma2);
                    const float W = spatial * normalWeight * depthWeight;
                    visSum += visIn.at(qx, qy) * W;
                    radSum = radSum + screen::texel3(radIn, qx, qy) * W;
                    total += W;
                }
            const float kept = 1.0f - total;
            out[0].at(x, y) = visSum + kept * centreVis;
            put(out[1], x, y, radSum + centreRad * kept, 1.0f);
        }
    return out;
}

// ssdo_fast_direct.glsl: inputs the pyramid's level 0, the normal and the sky.
Result<std::vector<HostImage>> ssdoFastDirect(const Context& ctx) {
    const auto& f = ctx.frame;
    CAVITY_TRY(screen::requireInput(ctx, 0, f.size[0], f.size[1], 1));
    CAVITY_TRY(screen::requireInput(ctx, 1, f.size[0], f.size[1], 3));
    const Levels* sky = skyLevels();
    if (!sky) return internal("reference ssdo_fast: no constant image 'sky' in screenSpaceConstants()");
    const FastMarch march(ctx);
    const float contrast = floatParam(ctx, "contrast"), lod = floatParam(ctx, "sky_lod");

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            FastMarch::Receiver r;
            if (!march.receiver(x, y, r)) {
                out[0].at(x, y) = 1.0f;
                put(out[1], x, y, sampleSky(*sky, skyUv(normalize(viewRay(f, x, y))), 0.0f), 1.0f);
                out[2].at(x, y, 0) = 1.0f;
                continue;
            }
            SkyGather g;
            for (int i = 0; i < march.n; ++i) {
                float senderDepth = 0.0f;
                const Sample s = march.sample(r, x, y, i, senderDepth);
                g.add(r.n, s.dir, sampleSky(*sky, skyUv(s.dir), lod), s.visible);
            }
            const float visibility = g.visibility(contrast);
            out[0].at(x, y) = visibility;
            put(out[1], x, y, g.radiance(march.n), 1.0f);
            const Vec2 oct = pyramid::octEncode(r.n);
            out[2].at(x, y, 0) = visibility, out[2].at(x, y, 1) = r.depth, out[2].at(x, y, 2) = oct.x, out[2].at(x, y, 3) = oct.y;
        }
    return out;
}

Result<std::vector<HostImage>> compositeSsdo(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 3, 3, 3, 4}));
    const HostImage& visibility = *ctx.inputs[0];
    const HostImage& radiance = *ctx.inputs[1];
    const HostImage& indirect = *ctx.inputs[2];
    const HostImage& normal = *ctx.inputs[3];
    const HostImage& albedo = *ctx.inputs[4];
    const auto& f = ctx.frame;
    const int mode = intParam(ctx, "ssdo_mode");
    const bool dither = intParam(ctx, "dither") != 0;
    const std::vector<float>& sh = array(ctx, "sky_sh");
    if (sh.size() < 36) return internal("reference composite_ssdo: sky_sh holds " + std::to_string(sh.size()) + " floats");

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            const Vec3 rad = screen::texel3(radiance, x, y);
            Vec3 c = rad;
            if (albedo.at(x, y, 3) >= 0.5f) {
                const Vec3 a = screen::texel3(albedo, x, y);
                const Vec3 ind = screen::texel3(indirect, x, y);
                if (mode == 0)
                    c = a * (skyAmbient(sh, screen::texel3(normal, x, y)) * visibility.at(x, y) + ind);
                else
                    c = a * (rad + ind);
            }
            if (dither) {
                const float offset = (ign(float(x) + 0.5f, float(y) + 0.5f) - 0.5f) * 0.003921569f;
                c = c + Vec3{offset, offset, offset};
            }
            put(out[0], x, y, {clamp(c.x, 0.0f, 1.0f), clamp(c.y, 0.0f, 1.0f), clamp(c.z, 0.0f, 1.0f)}, 1.0f);
        }
    return out;
}

}  // namespace cavity::reference
