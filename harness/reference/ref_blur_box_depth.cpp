// Reference of kernels/passes/blur_box_depth/blur_box_depth.glsl: seed 004's 4x4 box blur over
// the texels of the centre's surface. Which texels count is decided with
// the kernel's exact operations (positions rebuilt by viewFromDepth, the
// plane distances in the same order), so both sides average the same set.
#include "reference/portable_math.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <array>
#include <cmath>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
Vec3 normalizeExact(Vec3 v);
Vec3 viewFromDepth(const kernels::FrameUniforms& f, int tx, int ty, float depth);
Vec3 texel3(const HostImage& img, int x, int y);
}  // namespace screen

Result<std::vector<HostImage>> blurBoxDepth(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 1, 3}));
    const HostImage& ao = *ctx.inputs[0];
    const HostImage& depth = *ctx.inputs[1];
    const HostImage& normal = *ctx.inputs[2];
    const auto& f = ctx.frame;
    const int w = ao.width, h = ao.height;
    const float tolerance = 0.1f * floatParam(ctx, "radius");
    auto out = makeOutputs(ctx);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Vec3 nrm = screen::texel3(normal, x, y);
            if (depth.at(x, y) >= 1.0f || lengthSquared(nrm) == 0.0f) {
                out[0].at(x, y) = ao.at(x, y);
                continue;
            }
            nrm = screen::normalizeExact(nrm);
            const Vec3 p = screen::viewFromDepth(f, x, y, depth.at(x, y));
            const int sx = std::clamp(x - 2, 0, std::max(w - 4, 0));
            const int sy = std::clamp(y - 2, 0, std::max(h - 4, 0));
            float sum = 0.0f, count = 0.0f;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    const int tx = std::min(sx + i, w - 1), ty = std::min(sy + j, h - 1);
                    Vec3 nt = screen::texel3(normal, tx, ty);
                    if (depth.at(tx, ty) >= 1.0f || lengthSquared(nt) == 0.0f) continue;
                    nt = screen::normalizeExact(nt);
                    const Vec3 qp = screen::viewFromDepth(f, tx, ty, depth.at(tx, ty)) - p;
                    const float fromCentre = std::fabs(dot(nrm, qp)), fromTap = std::fabs(dot(nt, qp));
                    if (std::max(fromCentre, fromTap) > tolerance) continue;
                    sum += ao.at(tx, ty);
                    count += 1.0f;
                }
            out[0].at(x, y) = sum / count;
        }
    return out;
}

}  // namespace cavity::reference
