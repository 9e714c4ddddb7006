// The sky panorama's irradiance as spherical harmonics, for the SSDO
// composite's ambient term.
#include "screen_space_tables.h"

#include <cmath>
#include <numbers>

namespace cavity::kernels {

// Irradiance / pi of the panorama as 9 spherical-harmonic coefficients
// (Ramamoorthi & Hanrahan 2001), in the form include/sky.glsl's skyAmbient
// evaluates: sh[k].rgb = (A_l / pi) K_k^2 sum_texels L B_k dw, where B_k is
// the k-th polynomial (1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2), K_k its
// normalisation and A_l = pi, 2 pi / 3, pi / 4 the cosine lobe's bands.
std::vector<float> skySh() {
    static const std::vector<float> sh = [] {
        const double k[9] = {0.282095, 0.488603, 0.488603, 0.488603, 1.092548, 1.092548, 0.315392, 1.092548, 0.546274};
        const double band[9] = {1.0, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25};
        double acc[9][3] = {};
        const auto& top = skyLevels()[0];
        for (int y = 0; y < top.height; ++y)
            for (int x = 0; x < top.width; ++x) {
                const double u = (x + 0.5) / top.width, v = (y + 0.5) / top.height;
                double dx, dy, dz;
                skyDirection(u, v, dx, dy, dz);
                const double dw = (2 * std::numbers::pi / top.width) * (std::numbers::pi / top.height) * std::sin(v * std::numbers::pi);
                const double b[9] = {1, dy, dz, dx, dx * dy, dy * dz, 3 * dz * dz - 1, dx * dz, dx * dx - dy * dy};
                const float* p = &top.pixels[(size_t(y) * top.width + x) * 4];
                for (int i = 0; i < 9; ++i)
                    for (int c = 0; c < 3; ++c) acc[i][c] += p[c] * b[i] * dw;
            }
        std::vector<float> out(36, 0.0f);
        for (int i = 0; i < 9; ++i)
            for (int c = 0; c < 3; ++c) out[size_t(i) * 4 + c] = float(band[i] * k[i] * k[i] * acc[i][c]);
        return out;
    }();
    return sh;
}

}  // namespace cavity::kernels
