// References of kernels/passes/depth_from_position/depth_from_position.glsl, ssao_hemisphere.glsl and
// blur_box.glsl (the hemisphere SSAO lesson (docs/kernels.md)). Every value that picks a texel
// or decides a depth test is computed with the kernels' exact operations,
// so the verdicts agree sample for sample; what differs is only smoothstep,
// pow and the division by n (continuous, far under the 1e-3 tolerance).
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <array>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
Vec3 normalizeExact(Vec3 v);
void tangentFrame(Vec2 r, Vec3 n, Vec3& t, Vec3& b);
std::array<float, 4> mulPoint(const float* m, Vec3 v, float w);
Vec3 viewFromDepth(const kernels::FrameUniforms& f, int tx, int ty, float depth);
bool texelOfView(const kernels::FrameUniforms& f, Vec3 p, int& tx, int& ty);
float sampleHash(int x, int y, int i);
float smoothstep01(float x);
Vec3 texel3(const HostImage& img, int x, int y);
Status requireInput(const Context& ctx, size_t i, int width, int height, int minChannels);
}  // namespace screen

Result<std::vector<HostImage>> depthFromPosition(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {4}));
    const HostImage& position = *ctx.inputs[0];
    const auto& f = ctx.frame;
    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            float depth = 1.0f;
            if (!isBackground(position.at(x, y, 3))) {
                const auto clip = screen::mulPoint(f.proj, screen::texel3(position, x, y), 1.0f);
                depth = clip[2] * portableReciprocal(clip[3]);
            }
            out[0].at(x, y) = depth;
        }
    return out;
}

namespace {

// One sample s of the receiver at p (normal nrm): 1 where the stored surface
// at its texel occludes it, times the range weight; 0 off screen.
float sampleHit(const kernels::FrameUniforms& f, const HostImage& depthIn, const HostImage& normal, Vec3 p, Vec3 nrm,
                Vec3 s, float radius, float bias, bool rangeCheck) {
    float hit = 0.0f;
    int tx, ty;
    if (screen::texelOfView(f, s, tx, ty)) {
        tx = std::clamp(tx, 0, f.size[0] - 1);
        ty = std::clamp(ty, 0, f.size[1] - 1);
        const Vec3 q = screen::viewFromDepth(f, tx, ty, depthIn.at(tx, ty));
        // Behind the stored surface's plane (see the kernel), or
        // behind its depth where the normal faces away or is 0.
        // Below the receiver's tangent plane: never in front of the sample.
        Vec3 nq = screen::texel3(normal, tx, ty);
        bool occluded = false;
        if (dot(nrm, q - p) <= 0.0f) {
            occluded = false;
        } else if (lengthSquared(nq) > 0.0f && dot(nq, q) < 0.0f) {
            nq = screen::normalizeExact(nq);
            occluded = dot(nq, s - q) < -bias;
        } else {
            occluded = q.z >= s.z + bias;
        }
        float rangeWeight = 1.0f;
        if (rangeCheck) rangeWeight = screen::smoothstep01(radius / std::max(std::fabs(p.z - q.z), 1e-6f));
        hit = (occluded ? 1.0f : 0.0f) * rangeWeight;
    }
    return hit;
}

}  // namespace

Result<std::vector<HostImage>> hemisphere(const Context& ctx) {
    const auto& f = ctx.frame;
    CAVITY_TRY(screen::requireInput(ctx, 0, f.size[0], f.size[1], 1));
    CAVITY_TRY(screen::requireInput(ctx, 1, f.size[0], f.size[1], 3));
    CAVITY_TRY(screen::requireInput(ctx, 2, 4, 4, 2));
    const HostImage& depthIn = *ctx.inputs[0];
    const HostImage& normal = *ctx.inputs[1];
    const HostImage& noise = *ctx.inputs[2];
    const int n = std::clamp(intParam(ctx, "samples"), 1, 256);
    const float radius = floatParam(ctx, "radius");
    const float bias = floatParam(ctx, "bias");
    const float contrast = floatParam(ctx, "contrast");
    const bool jitter = intParam(ctx, "ign_jitter") != 0;
    const bool rangeCheck = intParam(ctx, "range_check") != 0;
    const bool stepJitter = intParam(ctx, "step_jitter") != 0;
    const std::vector<float>& kernel = array(ctx, "kernel");
    if (int(kernel.size()) < 4 * n)
        return internal("reference hemisphere: kernel array holds " + std::to_string(kernel.size() / 4) +
                        " points for " + std::to_string(n) + " samples");

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            const float depth = depthIn.at(x, y);
            Vec3 nrm = screen::texel3(normal, x, y);
            if (depth >= 1.0f || lengthSquared(nrm) == 0.0f) {
                out[0].at(x, y) = 1.0f;
                continue;
            }
            nrm = screen::normalizeExact(nrm);
            const Vec3 p = screen::viewFromDepth(f, x, y, depth);

            Vec2 r{noise.at(x & 3, y & 3, 0), noise.at(x & 3, y & 3, 1)};
            if (jitter) {
                const Vec2 cs = cosSinTurns(ign(float(x) + 0.5f, float(y) + 0.5f));
                r = {r.x * cs.x - r.y * cs.y, r.x * cs.y + r.y * cs.x};
            }
            Vec3 t, b;
            screen::tangentFrame(r, nrm, t, b);

            // Points grouped by direction, w = 1 closing a group: a
            // direction is blocked when any of its points is (see the kernel).
            float occlusion = 0.0f, directions = 0.0f, blocked = 0.0f;
            int inGroup = 0;
            for (int i = 0; i < n; ++i) {
                const float* k = &kernel[size_t(i) * 4];
                float lengthScale = radius;
                if (stepJitter)
                    lengthScale = radius * (1.0f - screen::sampleHash(x, y, int(directions)) * portableReciprocal(float(inGroup + 1)));
                const Vec3 s = p + (t * k[0] + b * k[1] + nrm * k[2]) * lengthScale;
                const float hit = sampleHit(f, depthIn, normal, p, nrm, s, radius, bias, rangeCheck);
                blocked = std::max(blocked, hit);
                ++inGroup;
                if (k[3] > 0.5f || i == n - 1) {
                    occlusion += blocked;
                    directions += 1.0f;
                    blocked = 0.0f;
                    inGroup = 0;
                }
            }
            const float ao = std::max(1.0f - occlusion / directions, 0.0f);
            out[0].at(x, y) = std::pow(ao, contrast);
        }
    return out;
}

Result<std::vector<HostImage>> blurBox(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1}));
    const HostImage& in = *ctx.inputs[0];
    const int w = in.width, h = in.height;
    auto out = makeOutputs(ctx);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // The window slides inwards at the border (blur_box.glsl).
            const int sx = std::clamp(x - 2, 0, std::max(w - 4, 0));
            const int sy = std::clamp(y - 2, 0, std::max(h - 4, 0));
            float sum = 0.0f;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) sum += in.at(std::min(sx + i, w - 1), std::min(sy + j, h - 1));
            out[0].at(x, y) = sum / 16.0f;
        }
    return out;
}

}  // namespace cavity::reference
