// References of the SSDO kernels (003_9aa4a2c3c5c6ee23.txt): ssdo_direct.glsl,
// blur_bilateral_ssdo.glsl, ssdo_indirect.glsl and composite_ssdo.glsl.
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
// under 0.5% next to the sun); visibility, a ratio of sums of the same
// weights, within 1e-3.
//
// The sky's levels come from the constant image's own generator, since a
// pass chain's read-back of the constant sky returns level 0 only.
#include "families.h"
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/pyramid.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <array>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
float inverseSqrt(float x);
Vec3 normalizeExact(Vec3 v);
bool texelOfView(const kernels::FrameUniforms& f, Vec3 p, int& tx, int& ty);
bool texelInside(const kernels::FrameUniforms& f, int tx, int ty);
float sampleHash(int x, int y, int i);
Vec3 texel3(const HostImage& img, int x, int y);
Status requireInput(const Context& ctx, size_t i, int width, int height, int minChannels);
}  // namespace screen

namespace {

constexpr float kPi = 3.14159265f;   // common.glsl's PI

// --- the sky (include/sky.glsl) ---------------------------------------------

using Levels = std::vector<kernels::ConstantImageDecl::Level>;

const Levels* skyLevels() {
    static const Levels levels = [] {
        for (const auto& c : kernels::screenSpaceConstants())
            if (c.name == "sky") return c.make({});
        return Levels{};
    }();
    return levels.empty() ? nullptr : &levels;
}

float portableAtan2(float y, float x) {
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float hi = std::max(ax, ay), lo = std::min(ax, ay);
    if (hi == 0.0f) return 0.0f;
    const float a = lo * portableReciprocal(hi);
    const float a2 = a * a;
    float r = a * (0.99997726f + a2 * (-0.33262347f + a2 * (0.19354346f + a2 * (-0.11643287f + a2 * (0.05265332f + a2 * -0.01172120f)))));
    if (ay > ax) r = 1.5707964f - r;
    if (x < 0.0f) r = 3.1415927f - r;
    return y < 0.0f ? -r : r;
}

Vec2 skyUv(Vec3 d) {
    const float u = portableAtan2(d.x, d.z) * 0.15915494f + 0.5f;
    const float s2 = std::max(1.0f - d.y * d.y, 0.0f);
    const float s = s2 > 0.0f ? s2 * screen::inverseSqrt(s2) : 0.0f;
    const float v = portableAtan2(s, d.y) * 0.31830987f;
    return {u, v};
}

Vec3 bilinear(const kernels::ConstantImageDecl::Level& l, Vec2 uv) {
    const float x = uv.x * float(l.width) - 0.5f, y = uv.y * float(l.height) - 0.5f;
    const float x0f = std::floor(x), y0f = std::floor(y);
    const float ax = x - x0f, ay = y - y0f;
    const int x0 = std::clamp(int(x0f), 0, l.width - 1), x1 = std::clamp(int(x0f) + 1, 0, l.width - 1);
    const int y0 = std::clamp(int(y0f), 0, l.height - 1), y1 = std::clamp(int(y0f) + 1, 0, l.height - 1);
    auto at = [&](int tx, int ty) {
        const float* p = &l.pixels[(size_t(ty) * l.width + tx) * 4];
        return Vec3{p[0], p[1], p[2]};
    };
    return mix(mix(at(x0, y0), at(x1, y0), ax), mix(at(x0, y1), at(x1, y1), ax), ay);
}

// textureLod(sky, uv, lod) with a linear, mip-linear, clamp-to-edge sampler.
Vec3 sampleSky(const Levels& levels, Vec2 uv, float lod) {
    lod = clamp(lod, 0.0f, float(levels.size() - 1));
    const int l0 = int(std::floor(lod));
    const float a = lod - float(l0);
    const Vec3 c0 = bilinear(levels[size_t(l0)], uv);
    if (a == 0.0f) return c0;
    const int l1 = std::min(l0 + 1, int(levels.size()) - 1);
    return mix(c0, bilinear(levels[size_t(l1)], uv), a);
}

float skyLuminance(Vec3 c) { return dot(c, Vec3{0.2126f, 0.7152f, 0.0722f}); }

Vec3 skyAmbient(const std::vector<float>& sh, Vec3 n) {
    auto c = [&](int k) { return Vec3{sh[size_t(k) * 4], sh[size_t(k) * 4 + 1], sh[size_t(k) * 4 + 2]}; };
    Vec3 e = c(0);
    e = e + c(1) * n.y;
    e = e + c(2) * n.z;
    e = e + c(3) * n.x;
    e = e + c(4) * (n.x * n.y);
    e = e + c(5) * (n.y * n.z);
    e = e + c(6) * (3.0f * n.z * n.z - 1.0f);
    e = e + c(7) * (n.x * n.z);
    e = e + c(8) * (n.x * n.x - n.y * n.y);
    return max(e, 0.0f);
}

// --- the sampling (include/ssdo.glsl) ---------------------------------------

struct Basis {
    Vec3 t, b, n;
    float phiTurns;
};

Basis ssdoBasis(int x, int y, Vec3 n) {
    const Vec3 up = std::fabs(n.y) < 0.999f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    Basis f;
    f.n = n;
    f.t = screen::normalizeExact(cross(up, n));
    f.b = cross(n, f.t);
    f.phiTurns = 0.5f * ign(float(x) + 0.5f, float(y) + 0.5f);
    return f;
}

Vec3 ssdoDirection(const Basis& f, int i, int count) {
    const float alpha = (float(i) + 0.5f) * portableReciprocal(float(count));
    const float cosE = 1.0f - alpha;
    const float sin2 = 1.0f - cosE * cosE;
    const float sinE = sin2 * screen::inverseSqrt(sin2);
    const float turns = (float(i) + 0.5f) * 0.7777778f + f.phiTurns;
    const Vec2 cs = cosSinTurns(turns);
    return f.t * (sinE * cs.x) + f.b * (sinE * cs.y) + f.n * cosE;
}

struct Sample {
    Vec3 dir;
    bool visible = true;
    int tx = -1, ty = -1;
};

bool ssdoBlocked(const kernels::FrameUniforms& fr, const HostImage& position, const HostImage& normal, const Basis& f,
                 Vec3 p, Vec3 point, float bias, int& tx, int& ty) {
    if (!screen::texelOfView(fr, point, tx, ty) || !screen::texelInside(fr, tx, ty)) return false;
    const Vec3 q = screen::texel3(position, tx, ty);
    const Vec3 m = screen::texel3(normal, tx, ty);
    if (isBackground(position.at(tx, ty, 3)) || lengthSquared(m) == 0.0f) return false;
    // Only a recorded point above the receiver's tangent plane occludes (see ssdo.glsl).
    if (dot(f.n, q - p) <= 0.0f) return false;
    if (dot(m, q) < 0.0f) return dot(m, point - q) < -bias;
    const float reach = lengthSquared(q);
    const float limit = reach * screen::inverseSqrt(reach) + bias;
    return lengthSquared(point) > limit * limit;
}

// Direction i marched in `steps` points (1: seed 003's one random length).
Sample ssdoSample(const kernels::FrameUniforms& fr, const HostImage& position, const HostImage& normal, const Basis& f,
                  Vec3 p, int x, int y, int i, int count, int steps, float radius, float bias) {
    Sample s;
    s.dir = ssdoDirection(f, i, count);
    const float u = screen::sampleHash(x, y, i);
    const float perStep = portableReciprocal(float(steps));
    for (int j = 0; j < steps; ++j) {
        const float lambda = radius * ((float(j + 1) - u) * perStep);
        const Vec3 point = p + s.dir * lambda;
        int tx = -1, ty = -1;
        if (ssdoBlocked(fr, position, normal, f, p, point, bias, tx, ty)) {
            s.visible = false;
            s.tx = tx, s.ty = ty;
            return s;
        }
    }
    return s;
}

// SkyGather and its functions in include/ssdo_sampling.glsl.
struct SkyGather {
    float total = 0.0f, visible = 0.0f;
    Vec3 direct;

    void add(Vec3 n, Vec3 dir, Vec3 sky, bool open) {
        const float cosTheta = std::max(dot(n, dir), 0.0f);
        const float weight = skyLuminance(sky) * cosTheta;
        total += weight;
        if (open) {
            visible += weight;
            direct = direct + sky * cosTheta;
        }
    }
    float visibility(float contrast) const {
        const float v = total > 0.0f ? visible / total : 1.0f;
        return clamp(std::pow(v, contrast), 0.0f, 1.0f);
    }
    Vec3 radiance(int count) const { return direct * (2.0f / float(count)); }
};

// bounceFrom() of include/ssdo_sampling.glsl.
Vec3 bounceFrom(Vec3 p, Vec3 n, Vec3 q, Vec3 m, Vec3 emitted, float radius, float distanceClamp) {
    const Vec3 toSender = q - p;
    const float dist = length(toSender);
    if (dist <= 0.0f) return {};
    const Vec3 w = toSender * (1.0f / dist);
    const float cosSender = std::max(dot(m, -w), 0.0f);
    const float cosReceiver = std::max(dot(n, w), 0.0f);
    const float falloff = std::max(1.0f - dist / radius, 0.0f);
    const float d = std::max(distanceClamp, dist);
    return emitted * (cosSender * cosReceiver * falloff / (d * d));
}

// What both ssdo_fast passes walk (include/ssdo_fast.glsl's FastReceiver):
// inputs 0 and 1 are the pyramid's level 0 and the normal.
struct FastMarch {
    const kernels::FrameUniforms& f;
    std::vector<HostImage> zmip;
    const HostImage& normal;
    pyramid::View view;
    int n, steps;
    float radius, bias;

    explicit FastMarch(const Context& ctx)
        : f(ctx.frame), zmip(pyramidLevels(*ctx.inputs[0], pyramid::levelCount())), normal(*ctx.inputs[1]),
          view(pyramid::view(f, int(zmip.size()))), n(std::clamp(intParam(ctx, "samples"), 1, 256)),
          steps(std::clamp(intParam(ctx, "steps"), 1, 16)), radius(floatParam(ctx, "radius")),
          bias(floatParam(ctx, "bias")) {}

    struct Receiver {
        float depth;
        Vec3 n, X;
        float level;   // N . X
        Basis basis;
    };

    // fastReceiver(): false on the background or a pixel without a normal.
    bool receiver(int x, int y, Receiver& r) const {
        r.depth = zmip[0].at(x, y);
        const Vec3 nrm = screen::texel3(normal, x, y);
        if (isBackground(r.depth) || lengthSquared(nrm) == 0.0f) return false;
        r.n = screen::normalizeExact(nrm);
        r.X = pyramid::positionAt(f, x, y, r.depth);
        r.level = dot(r.n, r.X);
        r.basis = ssdoBasis(x, y, r.n);
        return true;
    }

    // ssdoFastSample(): direction i marched, blocked by its first blocked
    // point, whose level-0 pixel (s.tx, s.ty) and depth are the sender.
    Sample sample(const Receiver& r, int x, int y, int i, float& senderDepth) const {
        Sample s;
        s.dir = ssdoDirection(r.basis, i, n);
        senderDepth = 0.0f;
        const float u = screen::sampleHash(x, y, i);
        const float perStep = portableReciprocal(float(steps));
        for (int j = 0; j < steps; ++j) {
            const float lambda = radius * ((float(j + 1) - u) * perStep);
            const Vec3 point = r.X + s.dir * lambda;
            if (pyramid::blocks(f, zmip, view, r.n, r.level, point, x, y, bias, s.tx, s.ty, senderDepth)) {
                s.visible = false;
                return s;
            }
        }
        s.tx = s.ty = -1;
        senderDepth = 0.0f;
        return s;
    }
};

Vec3 viewRay(const kernels::FrameUniforms& f, int x, int y) {
    const float ndcX = (float(x) + 0.5f) * f.invSize[0] * 2.0f - 1.0f;
    const float ndcY = (float(y) + 0.5f) * f.invSize[1] * 2.0f - 1.0f;
    return {ndcX * f.camera[0], -ndcY * f.camera[1], -1.0f};
}

void put(HostImage& img, int x, int y, Vec3 c, float a) {
    img.at(x, y, 0) = c.x, img.at(x, y, 1) = c.y, img.at(x, y, 2) = c.z, img.at(x, y, 3) = a;
}

}  // namespace

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
