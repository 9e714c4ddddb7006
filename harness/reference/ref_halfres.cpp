// References of kernels/passes/downsample_depth/downsample_depth.glsl, upsample_bilateral.glsl and
// upsample_composite.glsl (the two half-resolution tail passes fused).
// The downsample compares and copies, and moves the copied depth onto the
// half texel's ray in the kernel's exact operations. The upsample's
// weights are continuous (exp), except where every weight vanishes and it
// falls back to the half texel nearest in depth, a threshold the GPU and
// the CPU could straddle only within rounding of 1e-5.
//
// Sizes: the downsample's frame is the half frame (frame.size = half,
// srcSize = full), and its inputs are full size; the upsample's frame is
// the full one, and its half-size inputs are whatever size they are.
#include "reference/portable_math.h"
#include "reference/pyramid.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <cmath>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
Vec3 texel3(const HostImage& img, int x, int y);
bool halfTexelRayHit(const kernels::FrameUniforms& f, int x, int y, Vec3 p, Vec3 n, Vec3& hit);
Status requireInput(const Context& ctx, size_t i, int width, int height, int minChannels);
}  // namespace screen

namespace {

float blockDepth(float w) { return isBackground(w) ? 3.0e38f : w; }

// include/downsample.glsl's halfRayDepth: the copied texel's depth moved
// onto half texel (x, y)'s own centre ray.
float halfRayDepth(const kernels::FrameUniforms& f, int x, int y, Vec3 p, float w, Vec3 n) {
    if (isBackground(w)) return w;
    Vec3 hit;
    return screen::halfTexelRayHit(f, x, y, p, n, hit) ? -hit.z : w;
}

}  // namespace

Result<std::vector<HostImage>> downsampleDepth(const Context& ctx) {
    const auto& f = ctx.frame;
    const HostImage& position = *ctx.inputs[0];
    const HostImage& normal = *ctx.inputs[1];
    if ((position.width + 1) / 2 != f.size[0] || (position.height + 1) / 2 != f.size[1])
        return internal("reference " + ctx.kernel.name + ": a " + std::to_string(position.width) + "x" +
                        std::to_string(position.height) + " G-buffer does not halve to the frame's " +
                        std::to_string(f.size[0]) + "x" + std::to_string(f.size[1]) + " (give it the half-size frame)");
    CAVITY_TRY(screen::requireInput(ctx, 0, position.width, position.height, 4));
    CAVITY_TRY(screen::requireInput(ctx, 1, position.width, position.height, 3));
    const int fw = position.width, fh = position.height;

    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            const bool nearest = ((x + y) & 1) == 0;
            int bx = std::min(2 * x, fw - 1), by = std::min(2 * y, fh - 1);
            float best = blockDepth(position.at(bx, by, 3));
            for (int k = 1; k < 4; ++k) {
                const int tx = std::min(2 * x + (k & 1), fw - 1), ty = std::min(2 * y + (k >> 1), fh - 1);
                const float d = blockDepth(position.at(tx, ty, 3));
                if (nearest ? d < best : d > best) {
                    bx = tx, by = ty;
                    best = d;
                }
            }
            for (int c = 0; c < 4; ++c) {
                out[0].at(x, y, c) = position.at(bx, by, c);
                out[1].at(x, y, c) = c < normal.channels ? normal.at(bx, by, c) : 0.0f;
            }
            const Vec3 n = normal.channels >= 3 ? screen::texel3(normal, bx, by) : Vec3{0.0f, 0.0f, 0.0f};
            out[2].at(x, y) = halfRayDepth(f, x, y, screen::texel3(position, bx, by), position.at(bx, by, 3), n);
        }
    return out;
}

// downsample_pyramid: the same texels, and the depth as the pyramid's level
// 0 beside its pixel.
Result<std::vector<HostImage>> downsamplePyramid(const Context& ctx) {
    CAVITY_ASSIGN(auto out, downsampleDepth(ctx));
    pyramid::packSources(out[2]);
    return out;
}

namespace {

// upsample_bilateral's AO of every pixel of ctx.frame into `out` (1 channel);
// ctx's first five inputs are upsample_bilateral's.
Status upsampleInto(const Context& ctx, HostImage& out) {
    const auto& f = ctx.frame;
    const HostImage& aoHalf = *ctx.inputs[0];
    const HostImage& positionHalf = *ctx.inputs[1];
    const HostImage& position = *ctx.inputs[2];
    const HostImage& normal = *ctx.inputs[3];
    const HostImage& normalHalf = *ctx.inputs[4];
    const int hw = aoHalf.width, hh = aoHalf.height;
    CAVITY_TRY(screen::requireInput(ctx, 0, hw, hh, 1));
    CAVITY_TRY(screen::requireInput(ctx, 1, hw, hh, 4));
    CAVITY_TRY(screen::requireInput(ctx, 2, f.size[0], f.size[1], 4));
    CAVITY_TRY(screen::requireInput(ctx, 3, f.size[0], f.size[1], 3));
    CAVITY_TRY(screen::requireInput(ctx, 4, hw, hh, 3));
    const float tolerance = floatParam(ctx, "upsample_depth_tolerance");

    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            const Vec3 p = screen::texel3(position, x, y);
            const float pw = position.at(x, y, 3);
            const Vec3 nrm = screen::texel3(normal, x, y);
            if (isBackground(pw) || lengthSquared(nrm) == 0.0f) {
                out.at(x, y) = 1.0f;
                continue;
            }
            const float cx = float(x) * 0.5f - 0.25f, cy = float(y) * 0.5f - 0.25f;
            const int baseX = int(std::floor(cx)), baseY = int(std::floor(cy));
            const float fx = cx - float(baseX), fy = cy - float(baseY);
            const float tol = tolerance * pw;
            float sum = 0.0f, weightSum = 0.0f, fallback = 1.0f, fallbackDist = 3.0e38f;
            for (int k = 0; k < 4; ++k) {
                const int ox = k & 1, oy = k >> 1;
                const int tx = std::clamp(baseX + ox, 0, hw - 1), ty = std::clamp(baseY + oy, 0, hh - 1);
                const float ao = aoHalf.at(tx, ty);
                const float qw = positionHalf.at(tx, ty, 3);
                if (isBackground(qw)) continue;
                const Vec3 q = screen::texel3(positionHalf, tx, ty);
                const Vec3 m = screen::texel3(normalHalf, tx, ty);
                const float bilinear = (ox == 1 ? fx : 1.0f - fx) * (oy == 1 ? fy : 1.0f - fy);
                const float planeDist = std::fabs(dot(nrm, q - p)) / tol;
                const float depthWeight = std::exp(-0.5f * planeDist * planeDist);
                float cn = std::max(dot(nrm, m), 0.0f);
                cn *= cn;
                cn *= cn;
                const float w = bilinear * depthWeight * (cn * cn);
                sum += w * ao;
                weightSum += w;
                const float dz = std::fabs(qw - pw);
                if (dz < fallbackDist) {
                    fallbackDist = dz;
                    fallback = ao;
                }
            }
            out.at(x, y) = weightSum > 1e-5f ? sum / weightSum : fallback;
        }
    return {};
}

}  // namespace

Result<std::vector<HostImage>> upsampleBilateral(const Context& ctx) {
    auto out = makeOutputs(ctx);
    CAVITY_TRY(upsampleInto(ctx, out[0]));
    return out;
}

// upsample_composite.glsl: the upsample, then the composite of its AO in
// full float (the test rounds the stored AO to half as the R16F image does).
Result<std::vector<HostImage>> upsampleComposite(const Context& ctx) {
    const auto& f = ctx.frame;
    CAVITY_TRY(screen::requireInput(ctx, 5, f.size[0], f.size[1], 4));
    auto out = makeOutputs(ctx);   // color, ao
    CAVITY_TRY(upsampleInto(ctx, out[1]));
    compositeInto(ctx, out[1], *ctx.inputs[3], *ctx.inputs[5], out[0]);
    return out;
}

}  // namespace cavity::reference
