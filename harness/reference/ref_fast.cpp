// References of the fast variants: kernels/passes/depth_pyramid/depth_pyramid.glsl,
// ssao_alchemy_fast.glsl, ssao_hemisphere_fast.glsl and the separable blur pair
// (include/blur_separable.glsl). The pyramid's levels are rebuilt here from
// level 0, which is all a pass's readback holds: each level keeps one real
// texel of the level above, so the rebuild is exact.
#include "reference/alchemy_spiral.h"
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/pyramid.h"
#include "reference/refs.h"

#include <array>
#include <bit>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
Vec3 normalizeExact(Vec3 v);
float smoothstep01(float x);
float sampleHash(int x, int y, int i);
void tangentFrame(Vec2 r, Vec3 n, Vec3& t, Vec3& b);
}  // namespace screen

namespace pyramid {

namespace {

// include/pyramid.glsl's LOG_MAX_OFFSET.
constexpr int kLogMaxOffset = 3;

// GLSL findMSB of a non-negative int: -1 for 0.
int findMsb(int v) { return int(std::bit_width(unsigned(v))) - 1; }

float signNotNegative(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

}  // namespace

Vec3 positionAt(const kernels::FrameUniforms& f, int x, int y, float depth) {
    const float ndcX = (float(x) + 0.5f) * f.invSize[0] * 2.0f - 1.0f;
    const float ndcY = (float(y) + 0.5f) * f.invSize[1] * 2.0f - 1.0f;
    return {ndcX * f.camera[0] * depth, -ndcY * f.camera[1] * depth, -depth};
}

View view(const kernels::FrameUniforms& f, int levels) {
    return {0.5f * float(f.size[0]) * portableReciprocal(f.camera[0]),
            -0.5f * float(f.size[1]) * portableReciprocal(f.camera[1]), 0.5f * float(f.size[0]),
            0.5f * float(f.size[1]), levels - 1};
}

bool lookup(const kernels::FrameUniforms& f, const std::vector<HostImage>& zmip, const View& v, Vec3 s, int x, int y,
            int& sx, int& sy, float& zq) {
    sx = sy = -1;
    zq = 0.0f;
    if (s.z >= 0.0f) return false;
    const float inv = portableReciprocal(-s.z);
    const float spx = s.x * inv * v.toPixelX + v.centreX, spy = s.y * inv * v.toPixelY + v.centreY;
    const int px = int(std::floor(std::clamp(spx, -1.0f, float(f.size[0]))));
    const int py = int(std::floor(std::clamp(spy, -1.0f, float(f.size[1]))));
    if (px < 0 || py < 0 || px >= f.size[0] || py >= f.size[1]) return false;
    const int level = std::clamp(findMsb(std::max(std::abs(px - x), std::abs(py - y))) - kLogMaxOffset, 0, v.maxLevel);
    const HostImage& z = zmip[size_t(level)];
    int tx = std::min(px >> level, z.width - 1), ty = std::min(py >> level, z.height - 1);
    zq = z.at(tx, ty);
    if (isBackground(zq)) return false;
    sourcePixel(zmip, level, tx, ty);
    sx = tx, sy = ty;
    return true;
}

bool blocks(const kernels::FrameUniforms& f, const std::vector<HostImage>& zmip, const View& v, Vec3 N,
            float receiverLevel, Vec3 s, int x, int y, float bias, int& sx, int& sy, float& zq) {
    if (!lookup(f, zmip, v, s, x, y, sx, sy, zq)) return false;
    const float along = dot(N, positionAt(f, sx, sy, 1.0f));
    const float height = zq * along;
    if (along < 0.0f && height - dot(N, s) > bias) return true;
    if (zq + bias >= -s.z) return false;
    return along >= 0.0f || height - receiverLevel > bias;
}

// include/octahedral.glsl.
Vec2 octEncode(Vec3 n) {
    const float l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    Vec2 p{n.x / l1, n.y / l1};
    if (n.z < 0.0f) p = {(1.0f - std::fabs(p.y)) * signNotNegative(p.x), (1.0f - std::fabs(p.x)) * signNotNegative(p.y)};
    return p;
}

Vec3 octDecode(float px, float py) {
    Vec3 n{px, py, 1.0f - std::fabs(px) - std::fabs(py)};
    if (n.z < 0.0f) {
        const float x = (1.0f - std::fabs(n.y)) * signNotNegative(n.x);
        n.y = (1.0f - std::fabs(n.x)) * signNotNegative(n.y);
        n.x = x;
    }
    return normalize(n);
}

}  // namespace pyramid

namespace {


using pyramid::findMsb;
using pyramid::kLogMaxOffset;
using pyramid::octDecode;
using pyramid::octEncode;
using pyramid::packSources;
using pyramid::positionAt;
using pyramid::sourcePixel;

// A fast AO kernel's two outputs at (x, y): the AO, and the key the
// separable blur reads (AO, linear depth, octahedral normal).
void writeAo(std::vector<HostImage>& out, int x, int y, float ao, float depth, Vec3 N) {
    const Vec2 oct = octEncode(N);
    out[0].at(x, y) = ao;
    out[1].at(x, y, 0) = ao;
    out[1].at(x, y, 1) = depth;
    out[1].at(x, y, 2) = oct.x;
    out[1].at(x, y, 3) = oct.y;
}

// One axis of the separable blur at pixel (x, y): the key with its AO
// blurred, and in `value` the RGB of `with` blurred alike (blurredWith() of
// include/blur_separable.glsl; nothing when `with` is null).
std::array<float, 4> blurAlong(const Context& ctx, const HostImage& key, const HostImage* with, int x, int y, int ax,
                               int ay, Vec3& value) {
    const std::array<float, 4> centre{key.at(x, y, 0), key.at(x, y, 1), key.at(x, y, 2), key.at(x, y, 3)};
    auto tapValue = [&](int qx, int qy) { return with ? Vec3{with->at(qx, qy, 0), with->at(qx, qy, 1), with->at(qx, qy, 2)} : Vec3{}; };
    value = tapValue(x, y);
    const int r = intParam(ctx, "blur");
    if (r == 0 || isBackground(centre[1])) return centre;
    const Vec3 N = octDecode(centre[2], centre[3]);
    const float sigma = floatParam(ctx, "depth_sigma");
    const float twoSigma2 = 2.0f * sigma * sigma;
    const std::vector<float>& w = array(ctx, "weights");
    float sum = 0.0f, total = 0.0f;
    Vec3 valueSum;
    for (int t = -r; t <= r; ++t) {
        const int qx = x + ax * t, qy = y + ay * t;
        if (qx < 0 || qy < 0 || qx >= ctx.frame.size[0] || qy >= ctx.frame.size[1]) continue;
        const float tapDepth = key.at(qx, qy, 1);
        if (isBackground(tapDepth)) continue;
        const float dd = centre[1] - tapDepth;
        const float normalWeight = std::max(0.0f, dot(N, octDecode(key.at(qx, qy, 2), key.at(qx, qy, 3))));
        const float W = w[size_t(std::abs(t))] * normalWeight * std::exp(-dd * dd / twoSigma2);
        sum += key.at(qx, qy, 0) * W;
        valueSum = valueSum + tapValue(qx, qy) * W;
        total += W;
    }
    value = valueSum + value * (1.0f - total);
    return {sum + (1.0f - total) * centre[0], centre[1], centre[2], centre[3]};
}

// blur_separable_{x,y}.glsl, and with `withRadiance` blur_separable_ssdo_{x,y}.glsl
// (input 1 the radiance, blurred into output 1).
Result<std::vector<HostImage>> blurSeparable(const Context& ctx, bool horizontal, bool withRadiance) {
    CAVITY_TRY(withRadiance ? requireInputs(ctx, {4, 3}) : requireInputs(ctx, {4}));
    const int r = intParam(ctx, "blur");
    if (r > 0 && int(array(ctx, "weights").size()) <= r)
        return internal("reference " + ctx.kernel.name + ": too few weights for radius " + std::to_string(r));
    const HostImage* radiance = withRadiance ? ctx.inputs[1] : nullptr;
    auto out = makeOutputs(ctx);
    for (int y = 0; y < ctx.frame.size[1]; ++y)
        for (int x = 0; x < ctx.frame.size[0]; ++x) {
            Vec3 value;
            const auto v = blurAlong(ctx, *ctx.inputs[0], radiance, x, y, horizontal ? 1 : 0, horizontal ? 0 : 1, value);
            out[0].at(x, y, 0) = v[0];
            if (horizontal)
                for (int c = 1; c < 4; ++c) out[0].at(x, y, c) = v[size_t(c)];
            if (radiance) {
                out[1].at(x, y, 0) = value.x, out[1].at(x, y, 1) = value.y, out[1].at(x, y, 2) = value.z;
                out[1].at(x, y, 3) = 1.0f;
            }
        }
    return out;
}

}  // namespace

namespace {

// A pyramid build's outputs with level 0 made: each pixel's depth (the
// first input) beside the pixel itself. Its other levels are checked against
// pyramidLevels by the tests.
std::vector<HostImage> pyramidLevel0(const Context& ctx) {
    auto out = makeOutputs(ctx);
    for (int y = 0; y < ctx.frame.size[1]; ++y)
        for (int x = 0; x < ctx.frame.size[0]; ++x) out[0].at(x, y) = ctx.inputs[0]->at(x, y);
    packSources(out[0]);
    return out;
}

}  // namespace

Result<std::vector<HostImage>> depthPyramid(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 1}));
    return pyramidLevel0(ctx);
}

// depth_pyramid_single: the same level 0.
Result<std::vector<HostImage>> depthPyramidSingle(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1}));
    return pyramidLevel0(ctx);
}

// depth_pyramid_layered: that level 0, and again split into k x k layers
// (OutputDecl::layered), pixel p at layerTexel(p); the padding past the
// last pixel holds 0.
Result<std::vector<HostImage>> depthPyramidLayered(const Context& ctx) {
    CAVITY_ASSIGN(auto out, depthPyramidSingle(ctx));   // level 0, and the atlas all 0
    const int k = intParam(ctx, "interleave");
    for (int y = 0; y < ctx.frame.size[1]; ++y)
        for (int x = 0; x < ctx.frame.size[0]; ++x) {
            const auto [tx, ty] = pyramid::layerTexel(ctx.frame, k, x, y);
            out[1].at(tx, ty) = out[0].at(x, y);
        }
    return out;
}

Result<std::vector<HostImage>> alchemyFast(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 3}));
    const auto zmip = pyramidLevels(*ctx.inputs[0], pyramid::levelCount());
    const HostImage& normal = *ctx.inputs[1];
    const auto& f = ctx.frame;
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius");
    const float bias = floatParam(ctx, "bias");
    const float scale = floatParam(ctx, "scale");
    const float contrast = floatParam(ctx, "contrast");
    const int layers = intParam(ctx, "interleave");
    const float c = 0.1f * R;
    const float weight = 2.0f * kPi * c / float(n);
    const int maxLevel = int(zmip.size()) - 1;
    const std::vector<float>& spiral = array(ctx, "spiral");
    if (int(spiral.size()) < 4 * n) return internal("reference alchemy_fast: spiral table shorter than " + std::to_string(n));

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y) {
        for (int x = 0; x < f.size[0]; ++x) {
            const float d = zmip[0].at(x, y);
            if (isBackground(d)) {
                out[0].at(x, y) = 1.0f;
                out[1].at(x, y, 0) = 1.0f;
                continue;
            }
            const Vec3 X = positionAt(f, x, y, d);
            const Vec3 N{normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)};
            const float discScale = spiralDiscScale(f, R, n, d);
            const Vec2 phase = cosSinTurns(samplePhase(x, y, layers));
            float S = 0.0f;
            for (int i = 0; i < n; ++i) {
                // spiralSampleTurned() of the kernel: the table's direction turned by the phase.
                const float dx = spiral[size_t(i) * 4], dy = spiral[size_t(i) * 4 + 1];
                const float dirX = dx * phase.x - dy * phase.y, dirY = dx * phase.y + dy * phase.x;
                const float h = (float(i) + 0.5f) * discScale;
                const int sx = int(std::floor(float(x) + 0.5f + dirX * h));
                const int sy = int(std::floor(float(y) + 0.5f + dirY * h));
                if (sx < 0 || sy < 0 || sx >= f.size[0] || sy >= f.size[1]) continue;
                const int level = std::clamp(findMsb(int(h)) - kLogMaxOffset, 0, maxLevel);
                const HostImage& z = zmip[size_t(level)];
                int tx = std::min(sx >> level, z.width - 1), ty = std::min(sy >> level, z.height - 1);
                const float zs = z.at(tx, ty);
                if (isBackground(zs)) continue;
                sourcePixel(zmip, level, tx, ty);
                const Vec3 omega = positionAt(f, tx, ty, zs) - X;
                const float omega2 = lengthSquared(omega);
                if (omega2 > R * R) continue;
                S += weight * std::max(0.0f, dot(N, omega) - bias) / std::max(c * c, omega2);
            }
            writeAo(out, x, y, std::pow(std::max(0.0f, 1.0f - scale * S), contrast), d, N);
        }
    }
    return out;
}

// ssao_hemisphere_fast.glsl, operation for operation where a value picks a
// texel or decides a test.
Result<std::vector<HostImage>> hemisphereFast(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 3}));
    const auto zmip = pyramidLevels(*ctx.inputs[0], pyramid::levelCount());
    const HostImage& normal = *ctx.inputs[1];
    const auto& f = ctx.frame;
    const int n = std::clamp(intParam(ctx, "samples"), 1, 256);
    const float R = floatParam(ctx, "radius");
    const float bias = floatParam(ctx, "bias");
    const float contrast = floatParam(ctx, "contrast");
    const int layers = intParam(ctx, "interleave");
    const bool rangeCheck = intParam(ctx, "range_check") != 0;
    const bool stepJitter = intParam(ctx, "step_jitter") != 0;
    const std::vector<float>& kernel = array(ctx, "kernel");
    if (int(kernel.size()) < 4 * n) return internal("reference hemisphere_fast: kernel shorter than " + std::to_string(n));
    const pyramid::View view = pyramid::view(f, int(zmip.size()));

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y) {
        for (int x = 0; x < f.size[0]; ++x) {
            const float d = zmip[0].at(x, y);
            Vec3 N{normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)};
            if (isBackground(d) || lengthSquared(N) == 0.0f) {
                out[0].at(x, y) = 1.0f;
                out[1].at(x, y, 0) = 1.0f;
                continue;
            }
            N = screen::normalizeExact(N);
            const Vec3 X = positionAt(f, x, y, d);
            const float level = dot(N, X);
            Vec3 t, b;
            screen::tangentFrame(cosSinTurns(samplePhase(x, y, layers)), N, t, b);

            // One point's occlusion: occludedBy() of the kernel.
            auto occludedBy = [&](const float* k, float lengthScale) -> float {
                const Vec3 s = X + (t * k[0] + b * k[1] + N * k[2]) * lengthScale;
                int sx = -1, sy = -1;
                float zq = 0.0f;
                if (!pyramid::blocks(f, zmip, view, N, level, s, x, y, bias, sx, sy, zq)) return 0.0f;
                const float dz = std::fabs(d - zq);
                return rangeCheck && dz > R ? screen::smoothstep01(R / dz) : 1.0f;
            };
            // Rays of grouped points, skipped once fully blocked (see the kernel).
            float occlusion = 0.0f, directions = 0.0f, blocked = 0.0f, u = 0.0f;
            int inGroup = 0;
            for (int i = 0; i < n; ++i) {
                const float* k = &kernel[size_t(i) * 4];
                if (inGroup == 0 && stepJitter) u = screen::sampleHash(phaseCoord(x, layers), phaseCoord(y, layers), int(directions));
                if (blocked < 1.0f) {
                    float lengthScale = R;
                    if (stepJitter) lengthScale = R * (1.0f - u * portableReciprocal(float(inGroup + 1)));
                    blocked = std::max(blocked, occludedBy(k, lengthScale));
                }
                ++inGroup;
                if (k[3] > 0.5f || i == n - 1) {
                    occlusion += blocked;
                    directions += 1.0f;
                    blocked = 0.0f;
                    inGroup = 0;
                }
            }
            writeAo(out, x, y, std::pow(std::max(1.0f - occlusion / directions, 0.0f), contrast), d, N);
        }
    }
    return out;
}

Result<std::vector<HostImage>> blurSeparableX(const Context& ctx) { return blurSeparable(ctx, true, false); }
Result<std::vector<HostImage>> blurSeparableY(const Context& ctx) { return blurSeparable(ctx, false, false); }
Result<std::vector<HostImage>> blurSeparableSsdoX(const Context& ctx) { return blurSeparable(ctx, true, true); }
Result<std::vector<HostImage>> blurSeparableSsdoY(const Context& ctx) { return blurSeparable(ctx, false, true); }

std::vector<RefEntry> fastRefs() {
    return {{"depth_pyramid", depthPyramid},
            {"depth_pyramid_single", depthPyramidSingle},
            {"depth_pyramid_layered", depthPyramidLayered},
            {"alchemy_fast", alchemyFast},
            {"hemisphere_fast", hemisphereFast},
            {"blur_separable_x", blurSeparableX},
            {"blur_separable_y", blurSeparableY},
            {"blur_separable_ssdo_x", blurSeparableSsdoX},
            {"blur_separable_ssdo_y", blurSeparableSsdoY}};
}

}  // namespace cavity::reference
