// The fixed variants of the screen-space seeds, declared beside the
// seeds' own kernels (decl_screen_space.cpp), which stay as the named
// references every stored baseline and quality row was made against:
//
//   ssdo_marched (+ its bounce pass): seed 003's SSDO with each direction
//     marched in `steps` points out to R instead of one point at a random
//     length (include/ssdo.glsl says why);
//   blur_box_depth: seed 004's 4x4 box blur that keeps to the centre
//     texel's surface (blur_box_depth.glsl), picked by `depth_aware_box`;
//   depth_from_position_half: the half-resolution depth on each half
//     texel's own centre ray (depth_from_position_half.glsl), which the
//     hemisphere kernels read at half resolution.
//
// The variants are copies of the seed declarations with their names and
// defaults changed, so a parameter keeps one declaration (range, unit,
// help) for the seed and its variant.
#include "families.h"

#include <stdexcept>

namespace cavity::kernels {

namespace {

using gpu::Format;

// 4 points a direction: within 0.1 of the truth in every distance band at a
// 90 degree crease (tests/test_analytic.cpp, README Kernels); each step is
// a position and a normal fetch more, so the cost grows with it.
constexpr double kMarchedSteps = 4;

KernelDecl copyOf(const std::vector<KernelDecl>& seeds, const std::string& name) {
    for (const auto& k : seeds)
        if (k.name == name) return k;
    throw std::logic_error("decl_quality_variants: no seed kernel '" + name + "'");
}

void setDefault(KernelDecl& k, const std::string& param, double def) {
    for (auto& p : k.params)
        if (p.name() == param) {
            p.def = def;
            return;
        }
    throw std::logic_error("decl_quality_variants: kernel '" + k.name + "' has no parameter '" + param + "'");
}

// A seed SSDO pass made to march `steps` points a direction, and its cost
// with every direction marching all its steps (an open direction does):
// each step past the seed's one fetches a position and a normal more.
void marchEveryStep(KernelDecl& k) {
    setDefault(k, "steps", kMarchedSteps);
    k.cost = [seedCost = k.cost](const ParamValues& v, const PassShape& shape) {
        Cost c = seedCost(v, shape);
        const double extra = v.at("samples") * (v.at("steps") - 1);
        c.fetchesPerPixel += 2 * extra;
        c.bytesPerPixel += extra * (16 + kRgba16f);
        c.fetchSlotsPerPixel += extra * (fetchSlots(16) + fetchSlots(kRgba16f));
        return c;
    };
}

KernelDecl ssdoMarched(const std::vector<KernelDecl>& seeds) {
    KernelDecl k = copyOf(seeds, "ssdo");
    k.name = "ssdo_marched";
    k.summary = "SSDO with each of the n directions marched in 4 steps to R (published SSDO tests one point at a random length)";
    marchEveryStep(k);
    return k;
}

// The bounce must walk the very directions and steps the direct pass did
// (it re-uses their blocked points as senders): the pipeline runs
// "<ao kernel>_indirect" when there is one (harness/pipeline/pipelines.cpp), and
// this one's `steps` default is the direct pass's.
KernelDecl ssdoMarchedIndirect(const std::vector<KernelDecl>& seeds) {
    KernelDecl k = copyOf(seeds, "ssdo_indirect");
    k.name = "ssdo_marched_indirect";
    k.summary = "ssdo_marched's one-bounce indirect light, from the first blocked point of each marched direction";
    marchEveryStep(k);
    return k;
}

KernelDecl blurBoxDepth(const std::vector<KernelDecl>& seeds) {
    const KernelDecl hemisphere = copyOf(seeds, "hemisphere");
    KernelDecl k;
    k.name = "blur_box_depth";
    k.file = "blur_box_depth.glsl";
    k.summary = "4x4 box blur over the texels of the centre's surface only (within 0.1 R of each other's tangent planes)";
    k.role = Role::Blur;
    for (const auto& p : hemisphere.params)
        if (p.name() == "radius") k.params.push_back(p);
    k.inputs = {{"ao", {}}, {"depth", {}}, {"normal", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.cost = [](const ParamValues&, const PassShape&) {
        return Cost{48, 16 * (kR16f + kR32f + kRgba16f) + kR16f, 16 * (1 + 1 + fetchSlots(kRgba16f)),
                    kR16f + kR32f + kRgba16f + kR16f};
    };
    return k;
}

KernelDecl depthFromPositionHalf(const std::vector<KernelDecl>& seeds) {
    KernelDecl k = copyOf(seeds, "depth_from_position");
    k.name = "depth_from_position_half";
    k.file = "depth_from_position_half.glsl";
    k.summary = "half-resolution hardware depth where each half texel's centre ray meets its texel's tangent plane";
    k.inputs = {{"position", {}}, {"normal", {}}};
    k.cost = [](const ParamValues&, const PassShape&) {
        return Cost{2, kRgba32f + kRgba16f + kR32f, fetchSlots(kRgba32f) + fetchSlots(kRgba16f), kRgba32f + kRgba16f + kR32f};
    };
    return k;
}

}  // namespace

std::vector<KernelDecl> qualityVariantKernels() {
    const std::vector<KernelDecl> seeds = screenSpaceKernels();
    return {ssdoMarched(seeds), ssdoMarchedIndirect(seeds), blurBoxDepth(seeds), depthFromPositionHalf(seeds)};
}

}  // namespace cavity::kernels
