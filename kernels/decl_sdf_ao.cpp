// Declarations of the signed-distance AO family (the SDF AO reference (docs/kernels.md)):
// the classic five-tap normal probe and its five variants, and the ray-traced
// ground truth the quality measurements compare every AO kernel against.
//
// All of them read the G-buffer only for the surface point and normal, and
// evaluate the scene's distance function there, so they take the same
// --scene and --view as the G-buffer (one declaration, params.cpp).
// `samples` keeps the shared default (16); the seed's own counts
// (5, 6, 7, 6, 32, 32) are reproduced with --samples. `radius` and
// `strength` default to each seed variant's own constants: the same flag
// means "reach" and "how hard a shortfall counts" in every kernel, at the
// scale that variant was tuned for.
#include "families.h"

namespace cavity::kernels {

namespace {

using gpu::Format;

// One position and one normal read, one R16F AO written.
Cost gbufferPixelCost() {
    return Cost{2, kRgba32f + kRgba16f + kR16f, fetchSlots(kRgba32f) + fetchSlots(kRgba16f), kRgba32f + kRgba16f + kR16f};
}

KernelDecl sdfKernel(std::string name, std::string file, std::string summary, double radius, std::string radiusHelp,
                     double strength, std::string strengthHelp) {
    KernelDecl k;
    k.name = std::move(name);
    k.file = std::move(file);
    k.summary = std::move(summary);
    k.role = Role::Ao;
    k.sources = {"Evans, SIGGRAPH 2006 course"};
    k.params = {
        use("scene"),
        use("view"),
        use("samples", "distance-field probes"),
        use("radius", radius, std::move(radiusHelp)),
    };
    if (!strengthHelp.empty()) k.params.push_back(use("strength", strength, std::move(strengthHelp)));
    k.inputs = {{"position", {}}, {"normal", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.compileTime = {"scene"};
    // Reads its own pixel of the G-buffer; the distance probes are
    // arithmetic, not memory traffic, so the floor says nothing of them.
    k.cost = [](const ParamValues&, const PassShape&) { return gbufferPixelCost(); };
    return k;
}

KernelDecl groundTruth() {
    KernelDecl k;
    k.name = "ground_truth";
    k.file = "ground_truth.glsl";
    k.summary = "reference AO: cosine-weighted hemisphere visibility within R, 1024+ rays traced against the scene";
    // Named with --kernel it runs in the AO slot; sweeps over every AO
    // kernel leave it out (seconds per frame at 320x180 on a CPU renderer).
    k.role = Role::Reference;
    k.sources = {"Evans, SIGGRAPH 2006 course"};
    k.params = {
        use("scene"),
        use("view"),
        use("rays"),
        use("radius", "along each ray (the AO radius R of the screen-space kernels)"),
    };
    k.inputs = {{"position", {}}, {"normal", {}}};
    k.outputs = {{"ao", Format::R16F}};
    k.compileTime = {"scene"};
    k.cost = [](const ParamValues&, const PassShape&) { return gbufferPixelCost(); };
    return k;
}

}  // namespace

std::vector<KernelDecl> sdfAoKernels() {
    return {
        sdfKernel("sdf_classic", "sdf_ao_classic.glsl",
                  "SDF AO, classic: n probes along the normal, weighted sum of the distance shortfall", 0.13,
                  "height of the last probe along the normal (the source's 0.13)", 3.0,
                  "k in AO = 1 - k * sum of weighted shortfalls (the source's 3)"),
        sdfKernel("sdf_multiplicative", "sdf_ao_multiplicative.glsl",
                  "SDF AO, multiplicative: product of per-probe factors 1 - k (h - d) / h along the normal", 0.6,
                  "height of the last probe along the normal (the source's 6 x 0.1)", 0.2,
                  "k in each factor 1 - k (h - d) / h (the source's 0.2)"),
        sdfKernel("sdf_multiscale", "sdf_ao_multiscale.glsl",
                  "SDF AO, multi-scale: probes at doubling heights R/64 .. R, product of d / h, compressed ^0.3",
                  6.4, "height of the last probe; the first is R / 64 (the source's 0.1 .. 6.4)", 0, ""),
        sdfKernel("sdf_jittered", "sdf_ao_jittered.glsl",
                  "SDF AO, jittered: per-pixel jittered probes along the normal, shortfall weighted 1 / (1 + l)", 2.0,
                  "probes lie in (R / n, R (n + 1) / n) along the normal (the source's maxDist 4 x 0.5)", 1.0,
                  "k in AO = 1 - k * mean weighted shortfall"),
        sdfKernel("sdf_hemisphere", "sdf_ao_hemisphere.glsl",
                  "SDF AO, random hemisphere: random directions, quadratic heights, shortfall against h cos(theta)",
                  4.0, "height of the farthest probe, h = 0.01 + R t^2 (the source's 4)", 5.0,
                  "k in each probe's score 1 - k (h cos - d) / h (the source's 5)"),
        sdfKernel("sdf_fibonacci", "sdf_ao_fibonacci.glsl",
                  "SDF AO, Fibonacci hemisphere: Fibonacci-sphere directions at random distances up to R", 0.1,
                  "largest probe distance (the source's 0.1)", 3.0,
                  "k in each probe's score 1 - k (expected - d) / distance (the source's 3)"),
        groundTruth(),
    };
}

}  // namespace cavity::kernels
