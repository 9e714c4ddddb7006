// Declarations of the screen-space family: hemisphere-kernel SSAO with its
// 4x4 box blur (004_94976db8e6612027.txt), the half-resolution pair
// (downsample / bilateral upsample), and SSDO with its blur, bounce and
// composite (003_9aa4a2c3c5c6ee23.txt); and the images they read that the
// CPU makes: the 4x4 rotation-noise tile and the sky panorama with its mips.
//
// Parameters shared with the first slice (samples, radius, bias, contrast,
// blur, depth_sigma, dither) keep registry.cpp's ranges and units: one name
// is one flag with one value for every kernel of a pipeline. Defaults match
// too, except contrast (1 here, 1.5 for Alchemy; see hemisphere()).
#include "blur_weights.h"
#include "families.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cavity::kernels {

namespace {

using gpu::Format;

constexpr double kRgba32f = 16, kRgba16f = 8, kRgba8 = 4, kR32f = 4, kR16f = 2;
constexpr double kPi = 3.14159265358979323846;

// The hemisphere kernel array has room for the largest `samples` (256), so
// every allowed sample count is honoured as given, none clamped: 4 KiB of
// uniforms, well inside the 16 KiB every GL and Vulkan device offers.
constexpr int kMaxSamples = 256;

ParamDecl samplesParam(const std::string& help) {
    return makeParam("samples", ParamType::Int, 16, 1, kMaxSamples, "samples", help);
}
ParamDecl radiusParam(const std::string& help) {
    return makeParam("radius", ParamType::Float, 0.5, 0, 100, "world units", help, true);
}
ParamDecl biasParam(const std::string& help) {
    return makeParam("bias", ParamType::Float, 0.01, 0, 1, "world units", help);
}
ParamDecl contrastParam(double def, const std::string& help) {
    return makeParam("contrast", ParamType::Float, def, 0.1, 10, "", help);
}
// Points tested along each ray, out to R: hemisphere_cosine's march
// (cosineKernel), and SSDO's (include/ssdo.glsl), where 1 is seed 003's one
// point at a random length; ssdo_marched (decl_quality_variants.cpp)
// marches 4.
ParamDecl stepsParam(double def) {
    return makeParam("steps", ParamType::Int, def, 1, 16, "points",
                     "points tested along each ray, marched out to R (ssdo's 1: one point at a random length in (0, R])");
}

// --- deterministic random numbers for the CPU-made tables ------------------

uint32_t pcg(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1) from a fixed seed and three indices.
double unit(uint32_t seed, uint32_t a, uint32_t b, uint32_t c) {
    return double(pcg(pcg(pcg(seed + a) + b) + c) >> 8) / 16777216.0;
}

// --- hemisphere kernel -------------------------------------------------------

// n points in the unit +Z hemisphere, as vec4s (w = 1: each point is its
// own direction, see ssao_hemisphere.glsl), for a kernel of n
// samples (004_94976db8e6612027.txt, "Generate the sampling kernel"). A
// fixed seed gives the same kernel every run, so the image does not flicker
// between runs or frames. Directions come from rejection sampling in the
// half ball, so they are uniform (normalising points of a cube, as the seed
// does, crowds them towards the cube's diagonals); each point gets a random
// length in the volume, times lerp(0.1, 1, t^2) with t = i / n, which puts
// the first samples close to the surface, where contact occlusion changes
// fastest.
std::vector<float> hemisphereKernel(int n) {
    constexpr uint32_t kSeed = 0x5eed0004u;
    std::vector<float> out(size_t(kMaxSamples) * 4, 0.0f);
    n = std::clamp(n, 1, kMaxSamples);
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
    std::vector<float> out(size_t(kMaxSamples) * 4, 0.0f);
    n = std::clamp(n, 1, kMaxSamples);
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

// --- 4x4 rotation noise ----------------------------------------------------------

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

// --- sky panorama -------------------------------------------------------------------

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
    const double elev = 35.0 * kPi / 180.0, azim = 40.0 * kPi / 180.0;
    const double sx = std::cos(elev) * std::sin(azim), sy = std::sin(elev), sz = std::cos(elev) * std::cos(azim);
    const double cosSun = dx * sx + dy * sy + dz * sz;
    // Disc of 2.5 degrees radius: about 0.006 sr at radiance ~200, a third of
    // what an open upward surface receives, the rest from the sky.
    if (cosSun > std::cos(2.5 * kPi / 180.0)) c = {c.r + 200.0, c.g + 185.0, c.b + 160.0};
    // A soft glow around it.
    const double glow = 0.6 * std::pow(std::max(cosSun, 0.0), 24.0);
    return {c.r + glow, c.g + glow * 0.9, c.b + glow * 0.7};
}

// The direction at panorama coordinates (u, v); include/sky.glsl's skyUv
// is its inverse.
void skyDirection(double u, double v, double& dx, double& dy, double& dz) {
    const double phi = (u - 0.5) * 2.0 * kPi, theta = v * kPi;
    dx = std::sin(theta) * std::sin(phi);
    dy = std::cos(theta);
    dz = std::sin(theta) * std::cos(phi);
}

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

const std::vector<ConstantImageDecl::Level>& skyLevels() {
    static const std::vector<ConstantImageDecl::Level> levels = makeSky();
    return levels;
}

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
                const double dw = (2 * kPi / top.width) * (kPi / top.height) * std::sin(v * kPi);
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

// --- kernels -------------------------------------------------------------------

KernelDecl depthFromPosition() {
    KernelDecl k;
    k.name = "depth_from_position";
    k.file = "depth_from_position.glsl";
    k.summary = "hardware depth (proj p).z / w from the G-buffer position, 1 on background";
    k.role = "gbuffer";
    k.inputs = {{"position", {}}};
    k.outputs = {{"depth", Format::R32F}};
    k.cost = [](const ParamValues&) { return Cost{1, kRgba32f + kR32f, fetchSlots(kRgba32f), kRgba32f + kR32f}; };
    return k;
}

KernelDecl hemisphere() {
    KernelDecl k;
    k.name = "hemisphere";
    k.file = "ssao_hemisphere.glsl";
    k.summary = "hemisphere-kernel SSAO (Crytek / Chapman): n points in the normal hemisphere tested against depth";
    k.role = "ao";
    k.params = {
        samplesParam("kernel points per pixel (n)"),
        radiusParam("world-space hemisphere radius R"),
        biasParam("distance a sample must lie behind the stored surface's plane to be occluded (no self-shadowing)"),
        // 1 keeps seed 004's plain 1 - occluded / n; the curve is there for
        // seed 004's exercise 4 and for matching Alchemy's look (1.5 in
        // registry.cpp) in comparisons.
        contrastParam(1.0, "power curve on the result: AO = (1 - occluded / n)^k"),
        makeParam("ign_jitter", ParamType::Bool, 1, 0, 1, "",
              "rotate the 4x4 noise vector by interleaved gradient noise, hiding the tile's grid"),
        makeParam("range_check", ParamType::Bool, 1, 0, 1, "",
              "fade out occluders far from the surface in depth (smoothstep(0, 1, R / |dz|))"),
        makeParam("step_jitter", ParamType::Bool, 0, 0, 1, "",
              "move each direction's steps in by a random share of a step per pixel (hemisphere_cosine: 1)"),
        // The box blur pass after this one: seed 004's plain 4x4 box, or
        // blur_box_depth (decl_quality_variants.cpp), which keeps to the
        // centre's surface.
        makeParam("depth_aware_box", ParamType::Bool, 0, 0, 1, "",
              "box-blur only the texels of the centre's surface (blur_box_depth), not all 16 (seed 004)"),
    };
    gpu::SamplerState repeat;
    repeat.address = gpu::Address::Repeat;
    k.inputs = {{"depth", {}}, {"normal", {}}, {"noise4x4", repeat}};
    k.outputs = {{"ao", Format::R16F}};
    k.arrays = {{"kernel", kMaxSamples}};
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["kernel"] = hemisphereKernel(int(std::lround(v.at("samples"))));
    };
    k.cost = [](const ParamValues& v) {
        const double n = v.at("samples");
        // The 4x4 noise tile is 256 bytes in all: no DRAM traffic per pixel.
        return Cost{3 + n, kR32f + kRgba16f + kRgba32f + n * kR32f + kR16f,
                    fetchSlots(kR32f) + fetchSlots(kRgba16f) + fetchSlots(kRgba32f) + n * fetchSlots(kR32f),
                    kR32f + kRgba16f + kR16f};
    };
    return k;
}

// Seed 004's kernel with its sampling fixed (cosineKernel above): the same
// shader, noise tile, box blur and reference; only the kernel points differ.
KernelDecl hemisphereCosine() {
    KernelDecl k = hemisphere();
    k.name = "hemisphere_cosine";
    k.summary = "hemisphere-kernel SSAO walking n/steps cosine-weighted rays in `steps` (4) steps to R (blocked if any step is)";
    for (auto& p : k.params) {
        if (p.name == "samples") p.help = "kernel points per pixel (n): ceil(n / steps) rays of up to `steps` points";
        if (p.name == "step_jitter") p.def = 1;
        // The seed's box averaged the slats' thin occluders with what lies
        // behind them: 0.238 MAE on slats against 0.115 kept to one surface
        // (README, Kernels).
        if (p.name == "depth_aware_box") p.def = 1;
    }
    k.params.push_back(stepsParam(4));
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["kernel"] = cosineKernel(int(std::lround(v.at("samples"))), int(std::lround(v.at("steps"))));
    };
    return k;
}

KernelDecl blurBox() {
    KernelDecl k;
    k.name = "blur_box";
    k.file = "blur_box.glsl";
    k.summary = "4x4 box blur: averages exactly one period of the 4x4 noise tile";
    k.role = "blur";
    k.inputs = {{"ao", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.cost = [](const ParamValues&) { return Cost{16, 16 * kR16f + kR16f, 16 * fetchSlots(kR16f), kR16f + kR16f}; };
    return k;
}

KernelDecl downsampleDepth() {
    KernelDecl k;
    k.name = "downsample_depth";
    k.file = "downsample_depth.glsl";
    k.summary = "half-resolution G-buffer: one real texel of each 2x2 block, nearest and farthest in a checkerboard";
    k.role = "downsample";
    k.inputs = {{"position", {}}, {"normal", {}}};
    k.outputs = {{"position_half", Format::RGBA32F}, {"normal_half", Format::RGBA16F}};
    // Per half texel: 4 positions read, the chosen position and normal
    // fetched again (a cache hit), both written. DRAM: the 2x2 block of
    // both full-resolution images (every cache line of the normals is
    // touched even though one texel in four is used).
    k.cost = [](const ParamValues&) {
        return Cost{6, 4 * kRgba32f + kRgba16f + kRgba32f + kRgba16f,
                    4 * fetchSlots(kRgba32f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f),
                    4 * kRgba32f + 4 * kRgba16f + kRgba32f + kRgba16f};
    };
    return k;
}

KernelDecl upsampleBilateral() {
    KernelDecl k;
    k.name = "upsample_bilateral";
    k.file = "upsample_bilateral.glsl";
    k.summary = "joint bilateral upsample of half-resolution AO: bilinear x tangent-plane distance x normal weights";
    k.role = "upsample";
    k.params = {
        makeParam("upsample_depth_tolerance", ParamType::Float, 0.01, 0, 1, "fraction of depth",
              "distance of a half texel from the pixel's tangent plane, relative to depth, at which its "
              "weight falls to exp(-1/2)",
              true),
    };
    k.inputs = {{"ao_half", {}}, {"position_half", {}}, {"position", {}}, {"normal", {}}, {"normal_half", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.cost = [](const ParamValues&) {
        // DRAM: the half-resolution inputs are a quarter texel per pixel.
        return Cost{14, kRgba32f + kRgba16f + 4 * (kR16f + kRgba32f + kRgba16f) + kR16f,
                    fetchSlots(kRgba32f) + fetchSlots(kRgba16f) +
                        4 * (fetchSlots(kR16f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f)),
                    kRgba32f + kRgba16f + (kR16f + kRgba32f + kRgba16f) / 4 + kR16f};
    };
    return k;
}

gpu::SamplerState skySampler() {
    // Linear within and between levels. Clamp, not repeat: repeat would
    // also wrap v, blending the zenith row with the nadir row; the u seam
    // that clamping leaves unblended sits where visible surfaces do not look
    // (include/sky.glsl).
    gpu::SamplerState s;
    s.filter = gpu::Filter::Linear;
    s.address = gpu::Address::ClampToEdge;
    s.mipmaps = true;
    return s;
}

ParamDecl skyLodParam() {
    // Level 5 of the 256x128 panorama is 8x4 texels of 45 degrees, about
    // 0.5 sr each: the 0.4 sr that each of the default 16 samples stands
    // for (2 pi / n). At level 4 or lower the sun is a lobe that only a
    // sample or two per pixel hit, and the direct radiance shows the sample
    // pattern as rings on curved surfaces; at 6 the sky is 4x2 texels and
    // the sun's direction is mostly lost. Seed 003's "8 to 10" is the same
    // choice for a panorama 8-32 times wider. An integer level also keeps
    // the GPU's quantised mip blend out of the reference comparison.
    return makeParam("sky_lod", ParamType::Float, 5, 0, 8, "mip level",
                 "level of the sky panorama the SSDO samples read (0: 256x128, 8: 1x1)");
}

KernelDecl ssdo() {
    KernelDecl k;
    k.name = "ssdo";
    k.file = "ssdo_direct.glsl";
    k.summary = "screen-space directional occlusion (Ritschel et al. 2009): sky visibility and direct sky radiance";
    k.role = "ao";
    k.params = {
        samplesParam("hemisphere directions per pixel (n)"),
        radiusParam("world-space hemisphere radius R (sample lengths are drawn in (0, R])"),
        biasParam("distance a sample must lie behind the recorded surface's plane to be occluded"),
        contrastParam(1.0, "power curve on the visibility fraction: V^k (seed 003's contrast)"),
        skyLodParam(),
        stepsParam(1),
    };
    k.inputs = {{"position", {}}, {"normal", {}}, {"sky", skySampler()}};
    k.outputs = {{"visibility", Format::R16F}, {"radiance", Format::RGBA16F}};
    k.cost = [](const ParamValues& v) {
        const double n = v.at("samples");
        const double lod = v.at("sky_lod");
        const double skyTexels = lod == std::floor(lod) ? 4 : 8;   // bilinear, or trilinear
        // The sky panorama (256x128 RGBA32F and its mips, 0.7 MB) stays in
        // L2: no DRAM traffic per pixel.
        return Cost{2 + 3 * n, kRgba32f + kRgba16f + n * (kRgba32f + kRgba16f + skyTexels * kRgba32f) + kR16f + kRgba16f,
                    fetchSlots(kRgba32f) + fetchSlots(kRgba16f) +
                        n * (fetchSlots(kRgba32f) + fetchSlots(kRgba16f) + skyTexels / 4 * fetchSlots(kRgba32f)),
                    kRgba32f + kRgba16f + kR16f + kRgba16f};
    };
    return k;
}

KernelDecl blurBilateralSsdo() {
    KernelDecl k;
    k.name = "blur_bilateral_ssdo";
    k.file = "blur_bilateral_ssdo.glsl";
    k.summary = "bilateral blur of SSDO visibility and radiance together (the weights of blur_bilateral)";
    k.role = "blur";
    k.params = {
        makeParam("blur", ParamType::Int, 4, 0, 32, "px", "blur radius r: (2r+1)^2 taps, sigma = r/2; 0 passes through"),
        makeParam("depth_sigma", ParamType::Float, 0.1, 1e-4, 10, "world units",
              "sigma of the depth weight exp(-dd^2 / (2 sigma^2)) between a tap and the centre", true),
    };
    k.inputs = {{"visibility", {}}, {"radiance", {}}, {"position", {}}, {"normal", {}}};
    k.outputs = {{"visibility", Format::R16F}, {"radiance", Format::RGBA16F}};
    k.arrays = {{"weights", 9}};
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["weights"] = gaussianWeights(int(std::lround(v.at("blur"))));
    };
    k.cost = [](const ParamValues& v) {
        const double r = v.at("blur");
        const double taps = (2 * r + 1) * (2 * r + 1);
        return Cost{4 * taps, taps * (kR16f + kRgba16f + kRgba32f + kRgba16f) + kR16f + kRgba16f,
                    taps * (fetchSlots(kR16f) + fetchSlots(kRgba16f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f)),
                    kR16f + kRgba16f + kRgba32f + kRgba16f + kR16f + kRgba16f};
    };
    return k;
}

KernelDecl ssdoIndirect() {
    KernelDecl k;
    k.name = "ssdo_indirect";
    k.file = "ssdo_indirect.glsl";
    k.summary = "SSDO one-bounce indirect light from the occluded samples' blurred radiance and albedo";
    k.role = "indirect";
    k.params = {
        samplesParam("hemisphere directions per pixel (n); the same as the direct pass"),
        radiusParam("world-space hemisphere radius R; the same as the direct pass"),
        biasParam("distance a sample must lie behind the recorded surface's plane to be occluded"),
        makeParam("bounce_strength", ParamType::Float, 1, 0, 100, "", "scale of the indirect bounce (seed 003's strength)"),
        // R / 5 at the default R. With Alchemy's 0.1 R, senders almost
        // touching their receiver at a crease gave single-pixel sparks of
        // up to 2.6 on the corner and slats scenes (direct radiance is about
        // 1 there); R / 5 caps 1/d^2 at 25 / R^2, and the bounce still grows
        // smoothly towards the crease.
        makeParam("distance_clamp", ParamType::Float, 0.1, 0, 10, "world units",
              "lower bound of the sender-receiver distance in the form factor's 1/d^2", true),
        stepsParam(1),
    };
    k.inputs = {{"position", {}}, {"normal", {}}, {"albedo", {}}, {"radiance", {}}};
    k.outputs = {{"indirect", Format::RGBA16F}};
    // Upper bound: every sample occluded, so every one reads its sender.
    k.cost = [](const ParamValues& v) {
        const double n = v.at("samples");
        return Cost{2 + 4 * n, kRgba32f + kRgba16f + n * (kRgba32f + kRgba16f + kRgba16f + kRgba8) + kRgba16f,
                    fetchSlots(kRgba32f) + fetchSlots(kRgba16f) +
                        n * (fetchSlots(kRgba32f) + fetchSlots(kRgba16f) + fetchSlots(kRgba16f) + fetchSlots(kRgba8)),
                    kRgba32f + kRgba16f + kRgba16f + kRgba8 + kRgba16f};
    };
    return k;
}

KernelDecl compositeSsdo() {
    KernelDecl k;
    k.name = "composite_ssdo";
    k.file = "composite_ssdo.glsl";
    k.summary = "SSDO lit image: SH sky ambient x visibility, or the direct radiance, plus the bounce, on albedo";
    k.role = "composite";
    k.params = {
        makeParam("ssdo_mode", ParamType::Enum, 0, 0, 1, "",
              "visibility: SH sky ambient x visibility + bounce; radiance: direct sky radiance + bounce"),
        makeParam("dither", ParamType::Bool, 1, 0, 1, "", "add +-0.5/255 of interleaved gradient noise against 8-bit banding"),
    };
    k.params[0].choices = {"visibility", "radiance"};
    k.inputs = {{"visibility", {}}, {"radiance", {}}, {"indirect", {}}, {"normal", {}}, {"albedo", {}}};
    k.outputs = {{"color", Format::RGBA8}};
    k.arrays = {{"sky_sh", 9}};
    k.derive = [](const ParamValues&, std::map<std::string, std::vector<float>>& arrays) { arrays["sky_sh"] = skySh(); };
    k.cost = [](const ParamValues&) {
        return Cost{5, kR16f + kRgba16f + kRgba16f + kRgba16f + kRgba8 + kRgba8,
                    fetchSlots(kR16f) + 3 * fetchSlots(kRgba16f) + fetchSlots(kRgba8),
                    kR16f + kRgba16f + kRgba16f + kRgba16f + kRgba8 + kRgba8};
    };
    return k;
}

}  // namespace

ParamDecl makeParam(std::string name, ParamType type, double def, double min, double max, std::string unit,
                    std::string help, bool minExclusive) {
    ParamDecl p;
    p.name = std::move(name);
    p.type = type;
    p.def = def;
    p.min = min;
    p.max = max;
    p.unit = std::move(unit);
    p.help = std::move(help);
    p.minExclusive = minExclusive;
    return p;
}

std::vector<KernelDecl> screenSpaceKernels() {
    return {depthFromPosition(), hemisphere(),        hemisphereCosine(), blurBox(),      downsampleDepth(), upsampleBilateral(),
            ssdo(),              blurBilateralSsdo(), ssdoIndirect(), compositeSsdo()};
}

std::vector<ConstantImageDecl> screenSpaceConstants() {
    ConstantImageDecl noise;
    noise.name = "noise4x4";
    noise.format = Format::RGBA32F;
    noise.make = [](const ParamValues&) { return std::vector<ConstantImageDecl::Level>{noiseTile()}; };
    // RGBA32F rather than 16F: sampled with linear filtering, and the CPU
    // reference reads the very floats made here, no half rounding between.
    ConstantImageDecl sky;
    sky.name = "sky";
    sky.format = Format::RGBA32F;
    sky.make = [](const ParamValues&) { return skyLevels(); };
    return {noise, sky};
}

}  // namespace cavity::kernels
