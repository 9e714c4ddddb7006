// Declarations of the screen-space family: hemisphere-kernel SSAO with its
// 4x4 box blur (the hemisphere SSAO lesson (docs/kernels.md)), the half-resolution pair
// (downsample / bilateral upsample), and SSDO with its blur, bounce and
// composite (Ritschel et al., I3D 2009); and the images they read that the
// CPU makes (the 4x4 rotation-noise tile, the sky panorama with its mips),
// whose generators are in noise_tables.cpp, sky_panorama.cpp and sky_sh.cpp.
//
// Parameters are declared once in params.cpp; a kernel here says what it does
// with each (its note) and, where its seed needs it, its own default.
#include "blur_weights.h"
#include "families.h"
#include "screen_space_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cavity::kernels {

namespace {

using gpu::Format;

const int kMaxSamples = maxKernelPoints();

// --- kernels -------------------------------------------------------------------

KernelDecl depthFromPosition() {
    KernelDecl k;
    k.name = "depth_from_position";
    k.file = "depth_from_position.glsl";
    k.summary = "hardware depth (proj p).z / w from the G-buffer position, 1 on background";
    k.role = Role::GBuffer;
    k.inputs = {{"position", {}}};
    k.outputs = {{"depth", Format::R32F}};
    k.cost = [](const ParamValues&, const PassShape&) { return Cost{1, kRgba32f + kR32f, fetchSlots(kRgba32f), kRgba32f + kR32f}; };
    return k;
}

KernelDecl hemisphere() {
    KernelDecl k;
    k.name = "hemisphere";
    k.file = "ssao_hemisphere.glsl";
    k.summary = "hemisphere-kernel SSAO (Crytek / Chapman): n points in the normal hemisphere tested against depth";
    k.sources = {"Mittring, SIGGRAPH 2007 course", "Chapman, SSAO tutorial 2013"};
    k.role = Role::Ao;
    k.params = {
        use("samples", "kernel points in the normal hemisphere"),
        use("radius"),
        use("bias"),
        // 1 keeps seed 004's plain 1 - occluded / n; the curve is there for
        // seed 004's exercise 4 and for matching Alchemy's look (1.5 in
        // registry.cpp) in comparisons.
        use("contrast", "AO = (1 - occluded / n)^k"),
        use("ign_jitter"),
        use("range_check"),
        use("step_jitter"),
        use("depth_aware_box"),
    };
    gpu::SamplerState repeat;
    repeat.address = gpu::Address::Repeat;
    k.inputs = {{"depth", {}}, {"normal", {}}, {"noise4x4", repeat}};
    k.outputs = {{"ao", Format::R16F}};
    k.arrays = {{"kernel", kMaxSamples}};
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["kernel"] = hemisphereKernel(intValue(v, "samples"));
    };
    k.cost = [](const ParamValues& v, const PassShape&) {
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
    k.sources = {"Mittring, SIGGRAPH 2007 course", "Evans, SIGGRAPH 2006 course"};
    for (auto& p : k.params) {
        if (p.name() == "samples") p.note = "ceil(n / steps) cosine-weighted rays of up to `steps` points";
        if (p.name() == "step_jitter") p.def = 1;
        // The seed's box averaged the slats' thin occluders with what lies
        // behind them: 0.238 MAE on slats against 0.115 kept to one surface
        // (README, Kernels).
        if (p.name() == "depth_aware_box") p.def = 1;
    }
    k.params.push_back(use("steps", 4, "points along each ray; at a given n more steps mean fewer rays"));
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["kernel"] = cosineKernel(intValue(v, "samples"), intValue(v, "steps"));
    };
    return k;
}

KernelDecl blurBox() {
    KernelDecl k;
    k.name = "blur_box";
    k.file = "blur_box.glsl";
    k.summary = "4x4 box blur: averages exactly one period of the 4x4 noise tile";
    k.role = Role::Blur;
    k.inputs = {{"ao", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.cost = [](const ParamValues&, const PassShape&) { return Cost{16, 16 * kR16f + kR16f, 16 * fetchSlots(kR16f), kR16f + kR16f}; };
    return k;
}

KernelDecl downsampleDepth() {
    KernelDecl k;
    k.name = "downsample_depth";
    k.workgroup = {8, 8};   // between resolutions: slower in 16x16 (kernel.h)
    k.file = "downsample_depth.glsl";
    k.summary = "half-resolution G-buffer: one real texel of each 2x2 block, nearest and farthest in a checkerboard";
    k.role = Role::Downsample;
    k.inputs = {{"position", {}}, {"normal", {}}};
    k.outputs = {{"position_half", Format::RGBA32F}, {"normal_half", Format::RGBA16F}, {"linear_depth_half", Format::R32F}};
    // Per half texel: 4 positions read, the chosen position and normal
    // fetched again (a cache hit), the three written. DRAM: the 2x2 block of
    // both full-resolution images (every cache line of the normals is
    // touched even though one texel in four is used).
    k.cost = [](const ParamValues&, const PassShape&) {
        return Cost{6, 4 * kRgba32f + kRgba16f + kRgba32f + kRgba16f + kR32f,
                    4 * fetchSlots(kRgba32f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f),
                    4 * kRgba32f + 4 * kRgba16f + kRgba32f + kRgba16f + kR32f};
    };
    return k;
}

// downsample_depth and depth_pyramid_single in one pass
// (downsample_pyramid.glsl): the half-resolution G-buffer, and the pyramid
// built from the depth it picks. What a half-resolution fast pipeline runs
// unless it asks for the pyramid a level at a time or in layers
// (harness/pipeline/pipelines.cpp).
KernelDecl downsamplePyramid() {
    KernelDecl k;
    k.name = "downsample_pyramid";
    k.file = "downsample_pyramid.glsl";
    k.summary = "downsample_depth and depth_pyramid_single in one pass: the half-resolution G-buffer and its depth pyramid";
    k.role = Role::Downsample;
    k.workgroup = {8, 8};   // as downsample_depth
    k.inputs = {{"position", {}}, {"normal", {}}};
    OutputDecl zmip{"zmip", Format::RG32F, kPyramidLevels};
    zmip.oneDispatch = true;
    k.outputs = {{"position_half", Format::RGBA32F}, {"normal_half", Format::RGBA16F}, zmip};
    // downsample_depth's reads; its writes with the depth as level 0, and a
    // third of a depth more (1/4 + 1/16 + ...) for the smaller levels.
    k.cost = [](const ParamValues&, const PassShape&) {
        const double rest = (1 - std::pow(0.25, kPyramidLevels - 1)) / 3;
        const double writes = kRgba32f + kRgba16f + kRg32f + rest * kRg32f;
        return Cost{6, 4 * kRgba32f + kRgba16f + writes, 4 * fetchSlots(kRgba32f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f),
                    4 * kRgba32f + 4 * kRgba16f + writes};
    };
    return k;
}

// A pixel of the bilateral upsample: its own position and normal, and its
// share of the half texels (AO, position, normal) its workgroup blends. A
// compute workgroup of even sides loads them once into a tile of
// (W/2 + 2) x (H/2 + 2) (include/upsample.glsl); otherwise each pixel
// fetches its 4. DRAM: the half-resolution inputs are a quarter texel a
// pixel, and the AO is written.
Cost upsampleCost(const PassShape& shape) {
    const double w = shape.workgroup.x, h = shape.workgroup.y;
    const bool tiled = shape.compute && shape.workgroup.x % 2 == 0 && shape.workgroup.y % 2 == 0;
    const double texels = tiled ? (w / 2 + 2) * (h / 2 + 2) / (w * h) : 4;
    const double half = kR16f + kRgba32f + kRgba16f;
    return Cost{2 + 3 * texels, kRgba32f + kRgba16f + texels * half + kR16f,
                fetchSlots(kRgba32f) + fetchSlots(kRgba16f) +
                    texels * (fetchSlots(kR16f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f)),
                kRgba32f + kRgba16f + half / 4 + kR16f};
}

KernelDecl upsampleBilateral() {
    KernelDecl k;
    k.name = "upsample_bilateral";
    k.workgroup = {8, 8};   // between resolutions: slower in 16x16 (kernel.h)
    k.file = "upsample_bilateral.glsl";
    k.wholeWorkgroups = true;   // the half texels' tile (include/upsample.glsl)
    k.summary = "joint bilateral upsample of half-resolution AO: bilinear x tangent-plane distance x normal weights";
    k.role = Role::Upsample;
    k.params = {use("upsample_depth_tolerance"), use("fused_tail")};
    k.inputs = {{"ao_half", {}}, {"position_half", {}}, {"position", {}}, {"normal", {}}, {"normal_half", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.cost = [](const ParamValues&, const PassShape& shape) { return upsampleCost(shape); };
    return k;
}

// The fused half-resolution tail: upsample_bilateral and composite in one
// full-resolution pass (upsample_composite.glsl), picked by fused_tail.
KernelDecl upsampleComposite() {
    KernelDecl k;
    k.name = "upsample_composite";
    k.workgroup = {8, 8};   // between resolutions: slower in 16x16 (kernel.h)
    k.file = "upsample_composite.glsl";
    k.wholeWorkgroups = true;   // the half texels' tile (include/upsample.glsl)
    k.summary = "the half-resolution tail in one pass: joint bilateral upsample, then the composite of its AO";
    k.role = Role::Composite;
    k.params = {use("upsample_depth_tolerance"), use("dither"), use("fused_tail")};
    k.inputs = {{"ao_half", {}}, {"position_half", {}}, {"position", {}}, {"normal", {}}, {"normal_half", {}}, {"albedo", {}}};
    k.outputs = {{"color", Format::RGBA8}, {"ao", Format::R16F}};
    k.cost = [](const ParamValues&, const PassShape& shape) {
        // upsample_bilateral's, plus the albedo read and the colour written;
        // the AO is written once and never read back.
        Cost c = upsampleCost(shape);
        c.fetchesPerPixel += 1;
        c.bytesPerPixel += 2 * kRgba8;
        c.fetchSlotsPerPixel += fetchSlots(kRgba8);
        c.dramBytesPerPixel += 2 * kRgba8;
        return c;
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

KernelDecl ssdo() {
    KernelDecl k;
    k.name = "ssdo";
    k.file = "ssdo_direct.glsl";
    k.summary = "screen-space directional occlusion (Ritschel et al. 2009): sky visibility and direct sky radiance";
    k.sources = {"Ritschel et al., I3D 2009"};
    k.role = Role::Ao;
    k.params = {
        use("samples", "hemisphere directions"),
        use("radius", "world-space hemisphere radius R (sample lengths are drawn in (0, R])"),
        use("bias"),
        use("contrast", "power curve on the visibility fraction: V^k (published SSDO's contrast)"),
        use("sky_lod"),
        use("steps", 1, "1: published SSDO's one point at a random length in (0, R]"),
    };
    k.inputs = {{"position", {}}, {"normal", {}}, {"sky", skySampler()}};
    k.outputs = {{"visibility", Format::R16F}, {"radiance", Format::RGBA16F}};
    k.cost = [](const ParamValues& v, const PassShape&) {
        const double n = v.at("samples");
        const double sky = skyTexels(v);
        // The sky panorama (256x128 RGBA32F and its mips, 0.7 MB) stays in
        // L2: no DRAM traffic per pixel.
        return Cost{2 + 3 * n, kRgba32f + kRgba16f + n * (kRgba32f + kRgba16f + sky * kRgba32f) + kR16f + kRgba16f,
                    fetchSlots(kRgba32f) + fetchSlots(kRgba16f) +
                        n * (fetchSlots(kRgba32f) + fetchSlots(kRgba16f) + sky / 4 * fetchSlots(kRgba32f)),
                    kRgba32f + kRgba16f + kR16f + kRgba16f};
    };
    return k;
}

KernelDecl blurBilateralSsdo() {
    KernelDecl k;
    k.name = "blur_bilateral_ssdo";
    k.file = "blur_bilateral_ssdo.glsl";
    k.summary = "bilateral blur of SSDO visibility and radiance together (the weights of blur_bilateral)";
    k.role = Role::Blur;
    k.params = {
        use("blur", "(2r+1)^2 taps"),
        use("depth_sigma"),
    };
    k.inputs = {{"visibility", {}}, {"radiance", {}}, {"position", {}}, {"normal", {}}};
    k.outputs = {{"visibility", Format::R16F}, {"radiance", Format::RGBA16F}};
    k.arrays = {{"weights", 9}};
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["weights"] = gaussianWeights(intValue(v, "blur"));
    };
    k.cost = [](const ParamValues& v, const PassShape&) {
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
    k.role = Role::Indirect;
    k.params = {
        use("samples", "hemisphere directions, the same as the direct pass"),
        use("radius", "the same as the direct pass"),
        use("bias"),
        use("bounce_strength"),
        use("distance_clamp"),
        use("steps", 1, "the same as the direct pass"),
    };
    k.inputs = {{"position", {}}, {"normal", {}}, {"albedo", {}}, {"radiance", {}}};
    k.outputs = {{"indirect", Format::RGBA16F}};
    // Upper bound: every sample occluded, so every one reads its sender.
    k.cost = [](const ParamValues& v, const PassShape&) {
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
    k.role = Role::Composite;
    k.params = {use("ssdo_mode"), use("dither")};
    k.inputs = {{"visibility", {}}, {"radiance", {}}, {"indirect", {}}, {"normal", {}}, {"albedo", {}}};
    k.outputs = {{"color", Format::RGBA8}};
    k.arrays = {{"sky_sh", 9}};
    k.derive = [](const ParamValues&, std::map<std::string, std::vector<float>>& arrays) { arrays["sky_sh"] = skySh(); };
    k.cost = [](const ParamValues&, const PassShape&) {
        return Cost{5, kR16f + kRgba16f + kRgba16f + kRgba16f + kRgba8 + kRgba8,
                    fetchSlots(kR16f) + 3 * fetchSlots(kRgba16f) + fetchSlots(kRgba8),
                    kR16f + kRgba16f + kRgba16f + kRgba16f + kRgba8 + kRgba8};
    };
    return k;
}

}  // namespace

double skyTexels(const ParamValues& v) {
    const double lod = v.at("sky_lod");
    return lod == std::floor(lod) ? 4 : 8;
}

std::vector<KernelDecl> screenSpaceKernels() {
    return {depthFromPosition(), hemisphere(),        hemisphereCosine(), blurBox(),      downsampleDepth(), downsamplePyramid(), upsampleBilateral(),
            upsampleComposite(), ssdo(),              blurBilateralSsdo(), ssdoIndirect(), compositeSsdo()};
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
