// The sky panorama the SSDO kernels read (seed Ritschel et al., I3D 2009),
// made on the CPU with its mip chain.
#include "screen_space_tables.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cavity::kernels {

namespace {

// A latitude-longitude panorama of a clear sky, in view space (level camera,
// +Y the zenith; include/sky.glsl): u = 0.5 looks along +Z (behind the
// camera), v = 0 is the zenith. Radiance in linear RGB: a blue zenith fading
// to a pale horizon, a darker ground, and a sun behind the camera's right
// shoulder, 35 degrees up, so surfaces facing the camera and the floor both
// see it and occluders cut visible directional shadows in radiance mode.
constexpr int kSkyWidth = 256, kSkyHeight = 128;

struct Rgb {
    double r = 0, g = 0, b = 0;
};

Rgb skyRadiance(double dx, double dy, double dz) {
    const Rgb zenith{0.20, 0.36, 0.80}, horizon{0.78, 0.83, 0.90}, ground{0.30, 0.27, 0.24};
    Rgb c;
    if (dy >= 0) {
        const double t = std::pow(1.0 - dy, 3.0);
        c = {zenith.r + (horizon.r - zenith.r) * t, zenith.g + (horizon.g - zenith.g) * t,
             zenith.b + (horizon.b - zenith.b) * t};
    } else {
        // A short blend below the horizon, then ground darkening to the nadir.
        const double g = std::min(1.0, -dy * 6.0);
        const double shade = 1.0 + 0.3 * dy;
        c = {(horizon.r + (ground.r - horizon.r) * g) * shade, (horizon.g + (ground.g - horizon.g) * g) * shade,
             (horizon.b + (ground.b - horizon.b) * g) * shade};
    }
    const double elev = 35.0 * std::numbers::pi / 180.0, azim = 40.0 * std::numbers::pi / 180.0;
    const double sx = std::cos(elev) * std::sin(azim), sy = std::sin(elev), sz = std::cos(elev) * std::cos(azim);
    const double cosSun = dx * sx + dy * sy + dz * sz;
    // Disc of 2.5 degrees radius: about 0.006 sr at radiance ~200, a third of
    // what an open upward surface receives, the rest from the sky.
    if (cosSun > std::cos(2.5 * std::numbers::pi / 180.0)) c = {c.r + 200.0, c.g + 185.0, c.b + 160.0};
    // A soft glow around it.
    const double glow = 0.6 * std::pow(std::max(cosSun, 0.0), 24.0);
    return {c.r + glow, c.g + glow * 0.9, c.b + glow * 0.7};
}

}  // namespace

// The direction at panorama coordinates (u, v); include/sky.glsl's skyUv
// is its inverse.
void skyDirection(double u, double v, double& dx, double& dy, double& dz) {
    const double phi = (u - 0.5) * 2.0 * std::numbers::pi, theta = v * std::numbers::pi;
    dx = std::sin(theta) * std::sin(phi);
    dy = std::cos(theta);
    dz = std::sin(theta) * std::cos(phi);
}

namespace {

// Level 0 by 4x4 supersampling of each texel (the sun's edge would alias
// otherwise), then every level down to 1x1 by 2x2 box averaging: the
// kernels read it with textureLod at `sky_lod`, so each level must be the
// average of the one above, as a hardware mip generator would make it.
std::vector<ConstantImageDecl::Level> makeSky() {
    std::vector<ConstantImageDecl::Level> levels;
    ConstantImageDecl::Level top{kSkyWidth, kSkyHeight, std::vector<float>(size_t(kSkyWidth) * kSkyHeight * 4)};
    for (int y = 0; y < kSkyHeight; ++y)
        for (int x = 0; x < kSkyWidth; ++x) {
            Rgb sum;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    double dx, dy, dz;
                    skyDirection((x + (sx + 0.5) / 4.0) / kSkyWidth, (y + (sy + 0.5) / 4.0) / kSkyHeight, dx, dy, dz);
                    const Rgb c = skyRadiance(dx, dy, dz);
                    sum = {sum.r + c.r, sum.g + c.g, sum.b + c.b};
                }
            float* p = &top.pixels[(size_t(y) * kSkyWidth + x) * 4];
            p[0] = float(sum.r / 16), p[1] = float(sum.g / 16), p[2] = float(sum.b / 16), p[3] = 1.0f;
        }
    levels.push_back(std::move(top));
    while (levels.back().width > 1 || levels.back().height > 1) {
        const auto& src = levels.back();
        const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
        ConstantImageDecl::Level dst{w, h, std::vector<float>(size_t(w) * h * 4)};
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c) {
                    // A dimension already at 1 is not halved: its one texel
                    // counts twice, which leaves the average unchanged.
                    const int x0 = std::min(2 * x, src.width - 1), x1 = std::min(2 * x + 1, src.width - 1);
                    const int y0 = std::min(2 * y, src.height - 1), y1 = std::min(2 * y + 1, src.height - 1);
                    auto at = [&](int sx, int sy) { return double(src.pixels[(size_t(sy) * src.width + sx) * 4 + c]); };
                    dst.pixels[(size_t(y) * w + x) * 4 + c] = float((at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1)) / 4);
                }
        levels.push_back(std::move(dst));
    }
    return levels;
}

}  // namespace

const std::vector<ConstantImageDecl::Level>& skyLevels() {
    static const std::vector<ConstantImageDecl::Level> levels = makeSky();
    return levels;
}

}  // namespace cavity::kernels
