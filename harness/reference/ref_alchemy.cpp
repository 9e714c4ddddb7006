// Reference of kernels/ao/alchemy/ssao_alchemy.glsl (McGuire et al., HPG 2011). The
// sample pixels come out identical to the GPU's: the spiral angle, the disc
// scale and the sample position use only correctly rounded operations
// (portable_math.h, noise.h). What remains, pow() and the sums, differs by
// float rounding only.
#include "reference/alchemy_spiral.h"
#include "reference/noise.h"
#include "reference/portable_math.h"
#include "reference/refs.h"

namespace cavity::reference {

namespace {


Vec3 xyz(const HostImage& img, int x, int y) { return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)}; }

}  // namespace

Result<std::vector<HostImage>> alchemy(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {4, 3}));
    const HostImage& position = *ctx.inputs[0];
    const HostImage& normal = *ctx.inputs[1];
    const auto& f = ctx.frame;
    const int n = intParam(ctx, "samples");
    const float R = floatParam(ctx, "radius");
    const float bias = floatParam(ctx, "bias");
    const float scale = floatParam(ctx, "scale");
    const float contrast = floatParam(ctx, "contrast");
    const float c = 0.1f * R;
    const float weight = 2.0f * kPi * c / float(n);

    auto out = makeOutputs(ctx);
    HostImage& ao = out[0];
    for (int y = 0; y < f.size[1]; ++y) {
        for (int x = 0; x < f.size[0]; ++x) {
            const float d = position.at(x, y, 3);
            if (isBackground(d)) {
                ao.at(x, y) = 1.0f;
                continue;
            }
            const Vec3 X = xyz(position, x, y);
            const Vec3 N = xyz(normal, x, y);
            const float discScale = spiralDiscScale(f, R, n, d);
            const float u = pixelHash(x, y);

            float S = 0.0f;
            for (int i = 0; i < n; ++i) {
                const auto [sx, sy, h] = spiralSample(i, u, discScale, x, y);
                if (sx < 0 || sy < 0 || sx >= f.size[0] || sy >= f.size[1]) continue;
                if (isBackground(position.at(sx, sy, 3))) continue;
                const Vec3 omega = xyz(position, sx, sy) - X;
                const float omega2 = lengthSquared(omega);
                if (omega2 > R * R) continue;   // H = step(0, R - |omega|)
                S += weight * std::max(0.0f, dot(N, omega) - bias) / std::max(c * c, omega2);
            }
            ao.at(x, y) = std::pow(std::max(0.0f, 1.0f - scale * S), contrast);
        }
    }
    return out;
}

}  // namespace cavity::reference
