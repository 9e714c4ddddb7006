// The random tables the hemisphere SSAO kernels read (seed
// the hemisphere SSAO lesson (docs/kernels.md)): the sample kernels and the 4x4 rotation noise,
// from a fixed seed so that every run makes the same ones.
#include "screen_space_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cavity::kernels {

// The hemisphere kernel array has room for the largest `samples`, so every
// allowed sample count is honoured as given, none clamped: 4 KiB of
// uniforms, well inside the 16 KiB every GL and Vulkan device offers.
int maxKernelPoints() { return int(findParam("samples")->max); }

namespace {

uint32_t pcg(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1) from a fixed seed and three indices.
double unit(uint32_t seed, uint32_t a, uint32_t b, uint32_t c) {
    return double(pcg(pcg(pcg(seed + a) + b) + c) >> 8) / 16777216.0;
}

}  // namespace

// n points in the unit +Z hemisphere, as vec4s (w = 1: each point is its
// own direction, see ssao_hemisphere.glsl), for a kernel of n
// samples (the hemisphere SSAO lesson (docs/kernels.md), "Generate the sampling kernel"). A
// fixed seed gives the same kernel every run, so the image does not flicker
// between runs or frames. Directions come from rejection sampling in the
// half ball, so they are uniform (normalising points of a cube, as the seed
// does, crowds them towards the cube's diagonals); each point gets a random
// length in the volume, times lerp(0.1, 1, t^2) with t = i / n, which puts
// the first samples close to the surface, where contact occlusion changes
// fastest.
std::vector<float> hemisphereKernel(int n) {
    constexpr uint32_t kSeed = 0x5eed0004u;
    std::vector<float> out(size_t(maxKernelPoints()) * 4, 0.0f);
    n = std::clamp(n, 1, maxKernelPoints());
    for (int i = 0; i < n; ++i) {
        double x = 0, y = 0, z = 1;
        for (uint32_t attempt = 0; attempt < 64; ++attempt) {
            const double cx = unit(kSeed, uint32_t(i), 0, attempt) * 2 - 1;
            const double cy = unit(kSeed, uint32_t(i), 1, attempt) * 2 - 1;
            const double cz = unit(kSeed, uint32_t(i), 2, attempt);
            const double r2 = cx * cx + cy * cy + cz * cz;
            if (r2 > 1e-4 && r2 <= 1.0) {
                const double inv = 1.0 / std::sqrt(r2);
                x = cx * inv, y = cy * inv, z = cz * inv;
                break;
            }
        }
        const double t = double(i) / double(n);
        const double scale = (0.1 + 0.9 * t * t) * unit(kSeed, uint32_t(i), 3, 0);
        out[size_t(i) * 4 + 0] = float(x * scale);
        out[size_t(i) * 4 + 1] = float(y * scale);
        out[size_t(i) * 4 + 2] = float(z * scale);
        out[size_t(i) * 4 + 3] = 1.0f;
    }
    return out;
}

// The kernel of hemisphere_cosine: n points as ceil(n / s) directions of up
// to s steps each (`steps`, 4 by default: R/4, R/2, 3R/4 and R), w = 1 on a
// direction's last. The points are the cost, so at a given n more steps a
// ray means fewer rays a pixel (README, Kernels: the narrow gap).
// Seed 004's kernel counts the occluded share of the hemisphere's volume
// with points crowded near the centre, which is not the visibility an AO
// term stands for: at 0.25-0.5R from a concave 90 degree crease it read
// 0.99 where the cosine-weighted visibility within R is 0.73. A ray is
// blocked within R when something lies on it before R, so this kernel
// walks rays: cosine-weighted directions (each direction's weight in the
// irradiance is then the same, and the AO is the plain share of blocked
// ones, as the ground truth counts them), stratified on a Fibonacci lattice
// (u = (j + 0.5) / d, azimuth j / phi turns, r = sqrt(u)); the noise tile and
// IGN turn the whole set about N per pixel as for the seed's kernel. The last
// step at exactly R makes a solid occluder (a wall, a floor) count exactly
// when the ray meets it within R; the earlier steps catch thin ones.
std::vector<float> cosineKernel(int n, int stepsPerRay) {
    std::vector<float> out(size_t(maxKernelPoints()) * 4, 0.0f);
    n = std::clamp(n, 1, maxKernelPoints());
    const int steps = std::clamp(stepsPerRay, 1, n);
    const int dirs = (n + steps - 1) / steps;
    for (int i = 0; i < n; ++i) {
        const int j = i / steps, k = i % steps;
        const int inDir = std::min(steps, n - j * steps);
        const double u = (j + 0.5) / dirs;
        const double a = 2.0 * 3.14159265358979323846 * (j * 0.6180339887498949);
        const double r = std::sqrt(u), z = std::sqrt(std::max(0.0, 1.0 - u));
        const double len = double(k + 1) / double(inDir);
        out[size_t(i) * 4 + 0] = float(r * std::cos(a) * len);
        out[size_t(i) * 4 + 1] = float(r * std::sin(a) * len);
        out[size_t(i) * 4 + 2] = float(z * len);
        out[size_t(i) * 4 + 3] = k == inDir - 1 ? 1.0f : 0.0f;
    }
    return out;
}

// 16 random unit vectors in the view xy plane (z = 0), RGBA32F (seed 004,
// "Create the noise texture"): rotating the kernel about N by a different
// angle in each pixel of a 4x4 block turns banding into a 4-periodic noise
// that the 4x4 box blur removes exactly.
ConstantImageDecl::Level noiseTile() {
    constexpr uint32_t kSeed = 0x4015e44u;
    ConstantImageDecl::Level l{4, 4, std::vector<float>(64, 0.0f)};
    for (uint32_t i = 0; i < 16; ++i) {
        double x = 1, y = 0;
        for (uint32_t attempt = 0; attempt < 64; ++attempt) {
            const double cx = unit(kSeed, i, 0, attempt) * 2 - 1;
            const double cy = unit(kSeed, i, 1, attempt) * 2 - 1;
            const double r2 = cx * cx + cy * cy;
            if (r2 > 0.01 && r2 <= 1.0) {
                x = cx / std::sqrt(r2), y = cy / std::sqrt(r2);
                break;
            }
        }
        l.pixels[i * 4 + 0] = float(x);
        l.pixels[i * 4 + 1] = float(y);
    }
    return l;
}

std::vector<float> spiralTable() {
    std::vector<float> table(256 * 4, 0.0f);
    for (int i = 0; i < 256; ++i) {
        const double angle = 2 * 3.14159265358979323846 * std::fmod((i + 0.5) * 7.0 / 9.0, 1.0);
        table[size_t(i) * 4] = float(std::cos(angle));
        table[size_t(i) * 4 + 1] = float(std::sin(angle));
    }
    return table;
}

}  // namespace cavity::kernels
