// Reference of kernels/passes/blur_bilateral/blur_bilateral.glsl (McGuire et al., HPG 2011).
#include "reference/refs.h"
#include "reference/vec.h"

namespace cavity::reference {

Result<std::vector<HostImage>> blurBilateral(const Context& ctx) {
    CAVITY_TRY(requireInputs(ctx, {1, 4, 3}));
    const HostImage& aoIn = *ctx.inputs[0];
    const HostImage& position = *ctx.inputs[1];
    const HostImage& normal = *ctx.inputs[2];
    const auto& f = ctx.frame;
    const int r = intParam(ctx, "blur");
    const float sigma = floatParam(ctx, "depth_sigma");
    const float twoSigma2 = 2.0f * sigma * sigma;
    const std::vector<float>& w = array(ctx, "weights");
    if (r > 0 && int(w.size()) <= r)
        return internal("reference blur_bilateral: " + std::to_string(w.size()) + " weights for radius " + std::to_string(r));

    auto out = makeOutputs(ctx);
    HostImage& ao = out[0];
    for (int y = 0; y < f.size[1]; ++y) {
        for (int x = 0; x < f.size[0]; ++x) {
            const float centreAo = aoIn.at(x, y);
            const float d = position.at(x, y, 3);
            if (r == 0 || isBackground(d)) {
                ao.at(x, y) = centreAo;
                continue;
            }
            const Vec3 N{normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)};
            float sum = 0.0f, total = 0.0f;
            for (int ty = -r; ty <= r; ++ty) {
                for (int tx = -r; tx <= r; ++tx) {
                    const int qx = x + tx, qy = y + ty;
                    if (qx < 0 || qy < 0 || qx >= f.size[0] || qy >= f.size[1]) continue;
                    const float di = position.at(qx, qy, 3);
                    if (isBackground(di)) continue;
                    const Vec3 Ni{normal.at(qx, qy, 0), normal.at(qx, qy, 1), normal.at(qx, qy, 2)};
                    const float spatial = w[size_t(std::abs(tx))] * w[size_t(std::abs(ty))];
                    const float normalWeight = std::max(0.0f, dot(N, Ni));
                    const float depthWeight = std::exp(-(d - di) * (d - di) / twoSigma2);
                    const float W = spatial * normalWeight * depthWeight;
                    sum += aoIn.at(qx, qy) * W;
                    total += W;
                }
            }
            ao.at(x, y) = sum + (1.0f - total) * centreAo;   // rejected weight stays with the centre
        }
    }
    return out;
}

}  // namespace cavity::reference
