// Reference of kernels/passes/depth_from_position_half/depth_from_position_half.glsl: the half texel's
// centre ray met with its texel's tangent plane, then the hardware depth,
// in the kernel's exact operations (the hemisphere kernel's verdicts
// depend on every bit of it).
#include "reference/portable_math.h"
#include "reference/refs.h"
#include "reference/vec.h"

#include <array>
#include <cmath>

namespace cavity::reference {

namespace screen {   // refs_screen_space.cpp
std::array<float, 4> mulPoint(const float* m, Vec3 v, float w);
Vec3 texel3(const HostImage& img, int x, int y);
bool halfTexelRayHit(const kernels::FrameUniforms& f, int x, int y, Vec3 p, Vec3 n, Vec3& hit);
}  // namespace screen

Result<std::vector<HostImage>> depthFromPositionHalf(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {4, 3}));
    const HostImage& position = *ctx.inputs[0];
    const HostImage& normal = *ctx.inputs[1];
    const auto& f = ctx.frame;
    auto out = makeOutputs(ctx);
    for (int y = 0; y < f.size[1]; ++y)
        for (int x = 0; x < f.size[0]; ++x) {
            if (isBackground(position.at(x, y, 3))) {
                out[0].at(x, y) = 1.0f;
                continue;
            }
            const Vec3 p = screen::texel3(position, x, y), n = screen::texel3(normal, x, y);
            Vec3 surface = p, hit;
            if (screen::halfTexelRayHit(f, x, y, p, n, hit)) surface = hit;
            const auto clip = screen::mulPoint(f.proj, surface, 1.0f);
            out[0].at(x, y) = clip[2] * portableReciprocal(clip[3]);
        }
    return out;
}

}  // namespace cavity::reference
