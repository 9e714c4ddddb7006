// The kernel declarations: every kernel the harness can run, with its
// parameters (default, range, unit), its images and its derived uniforms.
// The CLI flags, the config parser, the uniform block and the error
// messages are all generated from these (kernel.h).
#include "blur_weights.h"
#include "families.h"
#include "kernel.h"
#include "package/package.h"
#include "screen_space_tables.h"

#include <cmath>
#include <stdexcept>

namespace cavity::kernels {

namespace {

using gpu::Format;

KernelDecl gbufferSdf() {
    KernelDecl k;
    k.name = "gbuffer_sdf";
    k.file = "gbuffer_sdf.glsl";
    k.summary = "G-buffer (view position and depth, normal, albedo, linear depth) by sphere tracing a signed-distance scene";
    k.role = Role::GBuffer;
    k.params = {use("scene"), use("view")};
    // linear_depth: the position's w again, on its own, as an engine's
    // depth buffer is: what the depth pyramid reads, at a quarter of the
    // position's bytes.
    k.outputs = {{"position", Format::RGBA32F},
                 {"normal", Format::RGBA16F},
                 {"albedo", Format::RGBA8},
                 {"linear_depth", Format::R32F}};
    k.compileTime = {"scene"};
    k.cost = [](const ParamValues&, const PassShape&) {
        return Cost{0, kRgba32f + kRgba16f + kRgba8 + kR32f, 0, kRgba32f + kRgba16f + kRgba8 + kR32f};
    };
    return k;
}

KernelDecl alchemy() {
    KernelDecl k;
    k.name = "alchemy";
    k.file = "ssao_alchemy.glsl";
    k.summary = "Alchemy screen-space ambient obscurance (McGuire et al. 2011): spiral samples in a world-radius disc";
    k.sources = {"McGuire et al., HPG 2011"};
    k.role = Role::Ao;
    // scale and contrast: the seed (McGuire et al., HPG 2011) tunes them per
    // camera distance (s = 2.0, k = 3.0 for a room seen from afar, 1.7 and
    // 2.2 close up) and says to expect to retune. Our cameras sit 1.5-4.5
    // units away with R = 0.5: at s = 1 the sphere's floor contact barely
    // shows; at s = 2 the slat recesses go black across their whole width.
    // s = 1.5, k = 1.5 keeps both legible, creases dark but not clipped.
    k.params = {
        use("samples", "spiral samples in a disc of world radius R"),
        use("radius"),
        use("bias"),
        use("scale"),
        use("contrast", 1.5, "k in A = max(0, 1 - s S)^k"),
    };
    k.inputs = {{"position", {}}, {"normal", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.cost = [](const ParamValues& v, const PassShape&) {
        const double n = v.at("samples");
        return Cost{2 + n, kRgba32f + kRgba16f + n * kRgba32f + kR16f,
                    fetchSlots(kRgba32f) + fetchSlots(kRgba16f) + n * fetchSlots(kRgba32f), kRgba32f + kRgba16f + kR16f};
    };
    return k;
}

KernelDecl blurBilateral() {
    KernelDecl k;
    k.name = "blur_bilateral";
    k.file = "blur_bilateral.glsl";
    k.summary = "bilateral blur of AO: Gaussian taps weighted by normal agreement and linear-depth difference";
    k.role = Role::Blur;
    k.params = {
        use("blur", "(2r+1)^2 taps"),
        use("depth_sigma"),
    };
    k.inputs = {{"ao", {}}, {"position", {}}, {"normal", {}}};
    k.outputs = {{"ao", Format::R16F}};
    // 33 weights (r up to 32) in vec4s.
    k.arrays = {{"weights", 9}};
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["weights"] = gaussianWeights(intValue(v, "blur"));
    };
    k.cost = [](const ParamValues& v, const PassShape&) {
        const double r = v.at("blur");
        const double taps = (2 * r + 1) * (2 * r + 1);
        return Cost{3 * taps, taps * (kR16f + kRgba32f + kRgba16f) + kR16f,
                    taps * (fetchSlots(kR16f) + fetchSlots(kRgba32f) + fetchSlots(kRgba16f)),
                    kR16f + kRgba32f + kRgba16f + kR16f};
    };
    return k;
}

KernelDecl composite() {
    KernelDecl k;
    k.name = "composite";
    k.file = "composite.glsl";
    k.summary = "albedo times sky/ground ambient times AO, with IGN dither before the 8-bit store";
    k.role = Role::Composite;
    k.params = {use("dither")};
    k.inputs = {{"ao", {}}, {"normal", {}}, {"albedo", {}}};
    k.outputs = {{"color", Format::RGBA8}};
    k.cost = [](const ParamValues&, const PassShape&) {
        return Cost{3, kR16f + kRgba16f + kRgba8 + kRgba8, fetchSlots(kR16f) + fetchSlots(kRgba16f) + fetchSlots(kRgba8),
                    kR16f + kRgba16f + kRgba8 + kRgba8};
    };
    return k;
}

// --- the fast variants: the same estimators on a depth pyramid --

KernelDecl depthPyramid() {
    KernelDecl k;
    k.name = "depth_pyramid";
    k.file = "depth_pyramid.glsl";
    k.summary = "linear-depth mip pyramid (RG32F, 5 levels, one real depth of each 2x2 block beside its pixel) for the fast AO kernels";
    k.role = Role::Pyramid;
    // Level l reads level l - 1 of its own output: "zmip" is both.
    k.inputs = {{"linear_depth", {}}, {"zmip", {gpu::Filter::Nearest, gpu::Address::ClampToEdge, true}}};
    k.outputs = {{"zmip", Format::RG32F, kPyramidLevels}};
    k.params = {use("pyramid_per_level")};
    // Per level-0 pixel: one R32F fetch and an 8-byte store at level 0,
    // and a third more of both (1/4 + 1/16 + ...) for the smaller levels.
    k.cost = [](const ParamValues&, const PassShape&) {
        const double rest = (1 - std::pow(0.25, kPyramidLevels - 1)) / 3;
        return Cost{1 + rest, kR32f + kRg32f + rest * 2 * kRg32f, fetchSlots(kR32f) + rest * fetchSlots(kRg32f),
                    kR32f + kRg32f + rest * 2 * kRg32f};
    };
    return k;
}

// The same pyramid in one dispatch (depth_pyramid_single.glsl): each level's
// texel written by the thread of the level-0 pixel it picked.
KernelDecl depthPyramidSingle() {
    KernelDecl k;
    k.name = "depth_pyramid_single";
    k.file = "depth_pyramid_single.glsl";
    k.summary = "depth_pyramid's levels in one dispatch: each texel written by the thread of the pixel it picks";
    k.role = Role::Pyramid;
    k.inputs = {{"linear_depth", {}}};
    OutputDecl zmip{"zmip", Format::RG32F, kPyramidLevels};
    zmip.oneDispatch = true;
    k.outputs = {zmip};
    k.params = {use("pyramid_per_level")};
    // Per level-0 pixel: one R32F fetch, an 8-byte store at level 0 and a
    // third of one (1/4 + 1/16 + ...) for the smaller levels; nothing is read twice.
    k.cost = [](const ParamValues&, const PassShape&) {
        const double rest = (1 - std::pow(0.25, kPyramidLevels - 1)) / 3;
        return Cost{1, kR32f + kRg32f + rest * kRg32f, fetchSlots(kR32f), kR32f + kRg32f + rest * kRg32f};
    };
    return k;
}

// depth_pyramid_single that also splits level 0 into the AO pass's
// interleaved layers ("zlayers", OutputDecl::layered): one more 4-byte
// store per pixel, in a pass that has just read the depth.
KernelDecl depthPyramidLayered() {
    KernelDecl k = depthPyramidSingle();
    k.name = "depth_pyramid_layered";
    k.summary = "depth_pyramid_single, and level 0 split into the AO pass's k x k interleaved layers (zlayers)";
    OutputDecl zlayers{"zlayers", Format::R32F};
    zlayers.layered = true;
    k.outputs.push_back(zlayers);
    k.params = {use("interleave")};
    k.cost = [](const ParamValues&, const PassShape&) {
        const double rest = (1 - std::pow(0.25, kPyramidLevels - 1)) / 3;
        const double bytes = kR32f + kRg32f + kR32f + rest * kRg32f;
        return Cost{1, bytes, fetchSlots(kR32f), bytes};
    };
    return k;
}

// A fast AO kernel's cost: the pixel's depth and normal, n RG32F samples
// of the pyramid (a depth and its source pixel), the AO and its packed key
// written; the pyramid's smaller levels are a third of level 0 in DRAM.
Cost pyramidAoCost(const ParamValues& v, const PassShape&) {
    const double n = v.at("samples");
    return Cost{2 + n, kRg32f + kRgba16f + n * kRg32f + kR16f + kRgba16f,
                fetchSlots(kRg32f) + fetchSlots(kRgba16f) + n * fetchSlots(kRg32f),
                kRg32f * 4 / 3 + kRgba16f + kR16f + kRgba16f};
}

KernelDecl alchemyFast() {
    KernelDecl k = alchemy();
    k.name = "alchemy_fast";
    k.file = "ssao_alchemy_fast.glsl";
    k.summary = "Alchemy obscurance on a linear-depth mip pyramid with a separable blur (after SAO, McGuire et al. 2012)";
    k.sources = {"McGuire et al., HPG 2011"};
    k.inputs = {{"zmip", {gpu::Filter::Nearest, gpu::Address::ClampToEdge, true}}, {"normal", {}}, {"zlayers", {}}};
    k.outputs = {{"ao", Format::R16F}, {"ao_key", Format::RGBA16F}};
    k.interleaved = true;
    // Sample i's spiral direction at phase 0, (cos, sin) of (i + 0.5) 7/9
    // turns, one vec4 each for samples up to 256: the kernel turns it by the
    // pixel's phase once computed, where evaluating cos and sin per sample
    // was a sixth of the pass on the H200 (docs/roofline.md). Whatever the
    // table's last bits, the shader and the CPU reference read the same ones.
    k.params.push_back(use("exact"));
    k.params.push_back(use("interleave"));
    k.compileTime = {"samples"};   // the sample loop unrolls (ssao_alchemy_fast.glsl)
    k.arrays = {{"spiral", 256}};
    k.derive = [](const ParamValues&, std::map<std::string, std::vector<float>>& arrays) {
        std::vector<float> table(256 * 4, 0.0f);
        for (int i = 0; i < 256; ++i) {
            const double angle = 2 * 3.14159265358979323846 * std::fmod((i + 0.5) * 7.0 / 9.0, 1.0);
            table[size_t(i) * 4] = float(std::cos(angle));
            table[size_t(i) * 4 + 1] = float(std::sin(angle));
        }
        arrays["spiral"] = std::move(table);
    };
    k.cost = pyramidAoCost;
    return k;
}

// hemisphere_cosine (seed 004 with its sampling fixed) on the pyramid: one
// RG32F fetch per point where it reads a depth and a normal
// (ssao_hemisphere_fast.glsl says what else differs, and why).
KernelDecl hemisphereFast() {
    KernelDecl k;
    k.name = "hemisphere_fast";
    k.file = "ssao_hemisphere_fast.glsl";
    k.summary = "hemisphere_cosine on a linear-depth mip pyramid, tested along the receiver's normal, with a separable blur";
    k.sources = {"Mittring, SIGGRAPH 2007 course", "Evans, SIGGRAPH 2006 course"};
    k.role = Role::Ao;
    k.params = {
        use("samples", "ceil(n / steps) cosine-weighted rays of up to `steps` points"),
        use("radius"),
        use("bias", "height above the point, along the receiver's normal, a stored point must rise to occlude it"),
        use("contrast", "AO = (1 - blocked rays / rays)^k"),
        use("range_check"),
        use("step_jitter"),
        use("steps", 4, "points along each ray; at a given n more steps mean fewer rays"),
        use("exact"),
        use("interleave"),
    };
    for (auto& p : k.params)
        if (p.name() == "step_jitter") p.def = 1;
    k.inputs = {{"zmip", {gpu::Filter::Nearest, gpu::Address::ClampToEdge, true}}, {"normal", {}}, {"zlayers", {}}};
    k.outputs = {{"ao", Format::R16F}, {"ao_key", Format::RGBA16F}};
    k.interleaved = true;
    // The point loop unrolls, and each point's place on its ray is a constant
    // (ssao_hemisphere_fast.glsl).
    k.compileTime = {"samples", "steps"};
    k.arrays = {{"kernel", maxKernelPoints()}};
    k.derive = [](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        arrays["kernel"] = cosineKernel(intValue(v, "samples"), intValue(v, "steps"));
    };
    k.cost = pyramidAoCost;   // every point is fetched
    return k;
}

// Texels of each tiled image a pixel of the separable blur fetches: its
// share of the workgroup's tile (include/blur_separable.glsl: a compute
// pass, r >= 1, the tile at most `limit` texels), or else one a tap. A
// workgroup hanging over the image's edge loads a whole tile for fewer
// pixels; the image's pixels are counted.
double blurTileFetches(double r, bool alongX, const PassShape& shape, double limit) {
    const double w = shape.workgroup.x, h = shape.workgroup.y;
    const double tile = alongX ? (w + 2 * r) * h : (h + 2 * r) * w;
    if (shape.compute && r >= 1 && tile <= limit) return tile / (w * h);
    return 2 * r + 1;
}

KernelDecl blurSeparable(const std::string& axis) {
    KernelDecl k = blurBilateral();
    k.name = "blur_separable_" + axis;
    k.file = "blur_separable_" + axis + ".glsl";
    k.summary = std::string(axis == "x" ? "horizontal" : "vertical") +
                " pass of the separable depth- and normal-aware blur of packed AO, depth and normal (2r+1 taps)";
    k.params[0].note = "2r+1 taps along each axis";
    k.inputs = {{"ao_key", {}}};
    k.outputs = {{axis == "x" ? "ao_key" : "ao", axis == "x" ? Format::RGBA16F : Format::R16F}};
    // Compute: the workgroup decodes its tile once into shared memory, and
    // the tap loop, of a compiled-in count, unrolls (include/blur_separable.glsl).
    k.compileTime = {"blur"};
    k.wholeWorkgroups = true;
    // Long along the axis: a 16x16 tile loads 1.5 texels a pixel at r = 4,
    // 32x8 1.25, 64x4 1.125. On the H200 blur_x was faster in 32x8 than in
    // 16x16 (study 2026-12-03_h200_blur_tile), and the pair faster again in
    // 64x4 and 4x64 (study 2026-12-04_h200_last_build).
    k.workgroup = axis == "x" ? Workgroup{64, 4} : Workgroup{4, 64};
    const double out = axis == "x" ? kRgba16f : kR16f;
    k.cost = [out, axis](const ParamValues& v, const PassShape& shape) {
        const double keys = blurTileFetches(v.at("blur"), axis == "x", shape, 768);
        return Cost{keys, keys * kRgba16f + out, keys * fetchSlots(kRgba16f), kRgba16f + out};
    };
    return k;
}


// The separable pair for ssdo_fast: the key's visibility and an RGBA16F
// radiance beside it, blurred with the same weights (blur_separable_ssdo_x.glsl).
KernelDecl blurSeparableSsdo(const std::string& axis) {
    KernelDecl k = blurSeparable(axis);
    k.name = "blur_separable_ssdo_" + axis;
    k.file = "blur_separable_ssdo_" + axis + ".glsl";
    k.summary = std::string(axis == "x" ? "horizontal" : "vertical") +
                " pass of the separable blur of SSDO visibility (in the packed key) and radiance (2r+1 taps)";
    k.inputs = {{"ao_key", {}}, {"radiance", {}}};
    if (axis == "x")
        k.outputs = {{"ao_key", Format::RGBA16F}, {"radiance", Format::RGBA16F}};
    else
        k.outputs = {{"visibility", Format::R16F}, {"radiance", Format::RGBA16F}};
    // The key from a tile; the radiance from the same tile along x (then of
    // at most 512 texels), a fetch a tap along y (blur_separable_ssdo_x.glsl).
    const double out = (axis == "x" ? kRgba16f : kR16f) + kRgba16f;
    k.cost = [out, axis](const ParamValues& v, const PassShape& shape) {
        const double r = v.at("blur");
        const double fetches = axis == "x" ? 2 * blurTileFetches(r, true, shape, 512)
                                           : blurTileFetches(r, false, shape, 768) + 2 * r + 1;
        return Cost{fetches, fetches * kRgba16f + out, fetches * fetchSlots(kRgba16f), 2 * kRgba16f + out};
    };
    return k;
}

// ssdo_marched (seed 003 with each direction marched in `steps` points) on
// the pyramid: one RG32F fetch per point where it reads an RGBA32F position
// and an RGBA16F normal (include/ssdo_fast.glsl), and the separable pair
// for both blurs. Its bounce pass is ssdo_fast_indirect.
const KernelDecl& qualityVariant(const std::string& name) {
    static const std::vector<KernelDecl> variants = qualityVariantKernels();
    for (const auto& k : variants)
        if (k.name == name) return k;
    throw std::logic_error("registry: no quality variant '" + name + "'");
}

KernelDecl ssdoFast() {
    KernelDecl k = qualityVariant("ssdo_marched");
    k.name = "ssdo_fast";
    k.file = "ssdo_fast_direct.glsl";
    k.summary = "ssdo_marched on a linear-depth mip pyramid, tested along the receiver's normal, with a separable blur";
    k.inputs = {{"zmip", {gpu::Filter::Nearest, gpu::Address::ClampToEdge, true}}, {"normal", {}}, k.inputs.at(2)};
    k.outputs = {{"visibility", Format::R16F}, {"radiance", Format::RGBA16F}, {"ao_key", Format::RGBA16F}};
    // The directions and their points compiled in (include/ssdo_fast.glsl);
    // the bounce pass walks the same points, compiled alike.
    k.compileTime = {"samples", "steps"};
    // Every direction marched to its last point (an open one is).
    k.cost = [](const ParamValues& v, const PassShape&) {
        const double points = v.at("samples") * v.at("steps"), sky = v.at("samples") * skyTexels(v);
        return Cost{2 + points + v.at("samples"), kRg32f + kRgba16f + points * kRg32f + sky * kRgba32f + kR16f + 2 * kRgba16f,
                    fetchSlots(kRg32f) + fetchSlots(kRgba16f) + points * fetchSlots(kRg32f) + sky / 4 * fetchSlots(kRgba32f),
                    kRg32f * 4 / 3 + kRgba16f + kR16f + 2 * kRgba16f};
    };
    return k;
}

KernelDecl ssdoFastIndirect() {
    KernelDecl k = qualityVariant("ssdo_marched_indirect");
    k.name = "ssdo_fast_indirect";
    k.file = "ssdo_fast_indirect.glsl";
    k.summary = "ssdo_fast's one-bounce indirect light, from the first blocked point of each marched direction";
    k.inputs = {{"zmip", {gpu::Filter::Nearest, gpu::Address::ClampToEdge, true}}, {"normal", {}}, {"albedo", {}},
                {"radiance", {}}};
    k.compileTime = {"samples", "steps"};
    // Upper bound: every point fetched, and every direction blocked, so
    // every one reads its sender's normal, radiance and albedo.
    k.cost = [](const ParamValues& v, const PassShape&) {
        const double n = v.at("samples"), points = n * v.at("steps");
        return Cost{2 + points + 3 * n, kRg32f + kRgba16f + points * kRg32f + n * (2 * kRgba16f + kRgba8) + kRgba16f,
                    fetchSlots(kRg32f) + fetchSlots(kRgba16f) + points * fetchSlots(kRg32f) +
                        n * (2 * fetchSlots(kRgba16f) + fetchSlots(kRgba8)),
                    kRg32f * 4 / 3 + 2 * kRgba16f + kRgba8 + kRgba16f};
    };
    return k;
}

}  // namespace

std::vector<KernelDecl>& registryForTests() {
    static std::vector<KernelDecl> kernels = [] {
        registryBuilding() = true;
        std::vector<KernelDecl> k = {gbufferSdf(), alchemy(), blurBilateral(), composite()};
        for (auto& d : screenSpaceKernels()) k.push_back(std::move(d));
        for (auto& d : qualityVariantKernels()) k.push_back(std::move(d));
        for (auto& d : {depthPyramid(), depthPyramidSingle(), depthPyramidLayered(), alchemyFast(), hemisphereFast(), blurSeparable("x"), blurSeparable("y"), ssdoFast(),
                        ssdoFastIndirect(), blurSeparableSsdo("x"), blurSeparableSsdo("y")})
            k.push_back(d);
        for (auto& d : sdfAoKernels()) k.push_back(std::move(d));
        appendBuiltInPackages(k);
        registryBuilding() = false;
        return k;
    }();
    return kernels;
}

const std::vector<KernelDecl>& all() { return registryForTests(); }

bool declares(const KernelDecl& k, const std::string& name) {
    for (const auto& p : k.params)
        if (p.name() == name) return true;
    return false;
}

bool evaluatesScene(const KernelDecl& k) { return k.role != Role::GBuffer && declares(k, "scene"); }

}  // namespace cavity::kernels
