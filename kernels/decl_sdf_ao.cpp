// The ray-traced ground truth the quality measurements compare every AO
// kernel against. It reads the G-buffer only for the surface point and
// normal and traces the scene's distance function from there, so it takes
// the same --scene and --view as the G-buffer (one declaration, params.cpp).
// The six SDF AO variants beside it are kernel packages (kernels/ao/sdf_*/),
// each with its seed's own radius and strength as its defaults.
#include "families.h"

namespace cavity::kernels {

namespace {

using gpu::Format;

// One position and one normal read, one R16F AO written.
Cost gbufferPixelCost() {
    return Cost{2, kRgba32f + kRgba16f + kR16f, fetchSlots(kRgba32f) + fetchSlots(kRgba16f), kRgba32f + kRgba16f + kR16f};
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

// The six SDF AO variants are kernel packages (kernels/ao/sdf_*/); the
// ground truth, which the quality measure names, stays here.
std::vector<KernelDecl> sdfAoKernels() { return {groundTruth()}; }

}  // namespace cavity::kernels
