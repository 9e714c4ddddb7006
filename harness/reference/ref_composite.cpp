// Reference of kernels/passes/composite/composite.glsl. Returns the float the GPU stores
// (dither included, clamped to [0, 1]); the 8-bit rounding of the target
// happens in the test's quantize().
#include "reference/noise.h"
#include "reference/refs.h"
#include "reference/vec.h"

namespace cavity::reference {

namespace {

const Vec3 kSky{0.85f, 0.92f, 1.0f};
const Vec3 kGround{0.55f, 0.50f, 0.45f};

}  // namespace

void compositeInto(const Context& ctx, const HostImage& aoIn, const HostImage& normal, const HostImage& albedo,
                   HostImage& color) {
    const auto& f = ctx.frame;
    const bool dither = intParam(ctx, "dither") != 0;
    for (int y = 0; y < f.size[1]; ++y) {
        for (int x = 0; x < f.size[0]; ++x) {
            Vec3 c = kSky;
            if (albedo.at(x, y, 3) >= 0.5f) {
                const Vec3 a{albedo.at(x, y, 0), albedo.at(x, y, 1), albedo.at(x, y, 2)};
                const float ambientMix = 0.5f + 0.5f * normal.at(x, y, 1);
                c = a * mix(kGround, kSky, ambientMix) * aoIn.at(x, y);
            }
            if (dither) {
                const float offset = (ign(float(x) + 0.5f, float(y) + 0.5f) - 0.5f) * 0.003921569f;
                c = c + Vec3{offset, offset, offset};
            }
            color.at(x, y, 0) = clamp(c.x, 0.0f, 1.0f);
            color.at(x, y, 1) = clamp(c.y, 0.0f, 1.0f);
            color.at(x, y, 2) = clamp(c.z, 0.0f, 1.0f);
            color.at(x, y, 3) = 1.0f;
        }
    }
}

Result<std::vector<HostImage>> composite(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 3, 4}));
    auto out = makeOutputs(ctx);
    compositeInto(ctx, *ctx.inputs[0], *ctx.inputs[1], *ctx.inputs[2], out[0]);
    return out;
}

}  // namespace cavity::reference
