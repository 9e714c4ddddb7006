// Which passes each configuration runs, wired by image name. Any kernel of
// role "ao" slots in: its inputs are matched by name to the G-buffer images
// ("position", "normal", "linear_depth", "depth" — which adds a depth pass — and CPU-made
// constants such as "noise4x4" or "sky"); a kernel with "visibility" and
// "radiance" outputs runs the SSDO chain (Ritschel et al., I3D 2009;
// docs/kernels.md, "Sources").
#include "pipeline/namespace.h"
#include "pipeline/pipeline.h"

#include <algorithm>

namespace cavity::pipeline {

namespace {

bool isConstant(const std::string& name) { return kernels::findConstant(name) != nullptr; }

// Whether the configuration asks for the pyramid a dispatch per level.
bool pyramidPerLevel(const RunConfig& c) { return c.params.count("pyramid_per_level") && c.params.at("pyramid_per_level") != 0; }

// The linear-depth pyramid of the fast kernels, from `linearDepth` (the
// G-buffer's, or the downsample's at half resolution) into `zmip`: one
// dispatch, or one per level with pyramid_per_level; with interleaved
// layers, one dispatch that also writes level 0 split into them.
PassSpec pyramidPass(const RunConfig& c, const std::string& linearDepth, const std::string& zmip, bool half) {
    if (interleaveOf(c) > 1)
        return {"pyramid", "depth_pyramid_layered", {linearDepth}, {zmip, "zlayers" + std::string(half ? "_half" : "")}, half};
    if (pyramidPerLevel(c))
        return {"pyramid", "depth_pyramid", {linearDepth, zmip}, {zmip}, half};
    return {"pyramid", "depth_pyramid_single", {linearDepth}, {zmip}, half};
}

bool isSsdo(const kernels::KernelDecl& k) {
    return k.outputs.size() >= 2 && k.outputs[0].name == "visibility" && k.outputs[1].name == "radiance";
}

// A kernel that packs its AO (or visibility) with the depth key the
// separable blur reads: its last output, "ao_key".
bool packsKey(const kernels::KernelDecl& k) { return k.outputs.size() >= 2 && k.outputs.back().name == "ao_key"; }

// The AO kernels, then the reference: a package's AO kernel joins the list
// before the ground truth, wherever the registry holds it.
std::string aoKernelNames() {
    std::string s;
    for (const auto role : {kernels::Role::Ao, kernels::Role::Reference})
        for (const auto& k : kernels::all())
            if (k.role == role) s += (s.empty() ? "" : ", ") + k.name;
    return s;
}

// The AO kernels that read only the G-buffer.
std::string screenSpaceAoNames() {
    std::string s;
    for (const auto& k : kernels::all())
        if (k.role == kernels::Role::Ao && !kernels::evaluatesScene(k)) s += (s.empty() ? "" : ", ") + k.name;
    return s;
}

}  // namespace

int interleaveOf(const RunConfig& c) { return kernels::interleaveValue(c.params); }

gpu::Stage passStage(const kernels::KernelDecl& k, const RunConfig& c) {
    const bool mipChain = std::any_of(k.outputs.begin(), k.outputs.end(), [](const auto& o) { return o.mipLevels > 1; });
    return mipChain || (k.interleaved && interleaveOf(c) > 1) ? gpu::Stage::Compute : c.stage;
}

bool pipelineReads(const RunConfig& c, const std::string& name) {
    for (const auto& spec : buildPasses(c))
        if (const auto* k = kernels::find(spec.kernel); k && kernels::declares(*k, name)) return true;
    return false;
}

void dropUnreadParams(RunConfig& c, const std::vector<std::string>& names) {
    for (const auto& name : names) {
        const auto it = c.params.find(name);
        if (it == c.params.end() || pipelineReads(c, name)) continue;
        RunConfig without = c;
        without.params.erase(name);
        if (!pipelineReads(without, name)) c.params.erase(it);
    }
}

bool supportsHalf(const std::string& kernel) {
    const auto* k = kernels::find(kernel);
    return k && !isSsdo(*k);
}

namespace {

// The SSDO chain: direct pass, its blur, the one-bounce indirect pass and its
// blur, the composite. Visibility plays the part of AO in the outputs a user
// and the gate see.
void ssdoPasses(const kernels::KernelDecl& k, const RunConfig& c, std::vector<PassSpec>& p) {
    std::vector<ImageRef> in;
    for (const auto& i : k.inputs) {
        in.push_back({i.name, isConstant(i.name) ? ImageSource::Constant : ImageSource::Pass});
        if (i.name == "zmip") p.push_back(pyramidPass(c, "linear_depth", "zmip", false));
    }
    // A variant's bounce pass is "<kernel>_indirect" (ssdo_marched_indirect): it
    // must walk the very points the direct pass did, so it carries the
    // variant's defaults. It reads what the direct pass read, plus the
    // albedo and the blurred radiance.
    const std::string indirectKernel = kernels::find(k.name + "_indirect") ? k.name + "_indirect" : "ssdo_indirect";
    std::vector<ImageRef> indirectIn;
    for (const auto& i : kernels::find(indirectKernel)->inputs)
        indirectIn.push_back(i.name == "radiance" ? ImageRef{"radiance_blur"} : ImageRef{i.name});
    // The bounce is filtered too, as SSDO's lighting pass reads a blurred
    // indirect map (Ritschel et al.): one sample meeting a sender at the
    // distance clamp carries up to (R / clamp)^2 times the others' weight, a
    // single-pixel firefly along every crease when left raw. The blur's
    // visibility output there is not used.
    if (packsKey(k)) {
        // The separable pair, weighted by the direct pass's key for both.
        p.push_back({"ao", k.name, in, {"ao", "radiance", "ao_key"}, false});
        p.push_back({"blur_x", "blur_separable_ssdo_x", {"ao_key", "radiance"}, {"ao_key_x", "radiance_x"}, false});
        p.push_back({"blur_y", "blur_separable_ssdo_y", {"ao_key_x", "radiance_x"}, {"ao_blur", "radiance_blur"}, false});
        p.push_back({"indirect", indirectKernel, indirectIn, {"indirect"}, false});
        p.push_back({"indirect_blur_x", "blur_separable_ssdo_x", {"ao_key", "indirect"}, {"indirect_key_x", "indirect_x"}, false});
        p.push_back({"indirect_blur_y", "blur_separable_ssdo_y", {"indirect_key_x", "indirect_x"}, {"indirect_vis", "indirect_blur"}, false});
    } else {
        p.push_back({"ao", k.name, in, {"ao", "radiance"}, false});
        p.push_back({"blur", "blur_bilateral_ssdo", {"ao", "radiance", "position", "normal"}, {"ao_blur", "radiance_blur"}, false});
        p.push_back({"indirect", indirectKernel, indirectIn, {"indirect"}, false});
        p.push_back({"indirect_blur", "blur_bilateral_ssdo", {"ao_blur", "indirect", "position", "normal"}, {"indirect_vis", "indirect_blur"}, false});
    }
    p.push_back({"composite", "composite_ssdo", {"ao_blur", "radiance_blur", "indirect_blur", "normal", "albedo"}, {"color"}, false});
}

// Whether the half-resolution downsample also builds the pyramid
// (downsample_pyramid): for a kernel that reads it, unless the pyramid is
// asked for a level at a time or in interleaved layers, which its own pass
// builds.
bool downsampleBuildsPyramid(const kernels::KernelDecl& k, const RunConfig& c) {
    const bool readsPyramid =
        std::any_of(k.inputs.begin(), k.inputs.end(), [](const kernels::InputDecl& i) { return i.name == "zmip"; });
    return readsPyramid && !pyramidPerLevel(c) && interleaveOf(c) == 1;
}

// A screen-space AO kernel's inputs at its resolution, and the passes that
// make them: the depth (put back on each half texel's own ray at half
// resolution: depth_from_position_half.glsl says why) and the linear-depth
// pyramid of the fast kernels, all its levels in one pass (at half
// resolution mostly the downsample's).
std::vector<ImageRef> aoInputs(const kernels::KernelDecl& k, const RunConfig& c, bool half, std::vector<PassSpec>& p) {
    const std::string suffix = half ? "_half" : "";
    const std::string position = "position" + suffix, normal = "normal" + suffix;
    std::vector<ImageRef> in;
    for (const auto& i : k.inputs) {
        if (i.name == "position") in.push_back(position);
        else if (i.name == "normal") in.push_back(normal);
        else if (i.name == "linear_depth") in.push_back("linear_depth" + suffix);
        else if (i.name == "depth") in.push_back("depth" + suffix);
        else if (i.name == "zmip") in.push_back("zmip" + suffix);
        // The depth split into interleaved layers, or with none the pyramid,
        // whose level 0 the kernel then reads in place.
        else if (i.name == "zlayers") in.push_back((interleaveOf(c) > 1 ? "zlayers" : "zmip") + suffix);
        else if (isConstant(i.name)) in.push_back({i.name, ImageSource::Constant});
        else in.push_back(i.name);
    }
    for (const auto& i : k.inputs) {
        if (i.name == "depth") {
            if (half)
                p.push_back({"depth", "depth_from_position_half", {position, normal}, {"depth" + suffix}, true});
            else
                p.push_back({"depth", "depth_from_position", {position}, {"depth"}, false});
        }
        if (i.name == "zmip" && !(half && downsampleBuildsPyramid(k, c)))
            p.push_back(pyramidPass(c, "linear_depth" + suffix, "zmip" + suffix, half));
    }
    return in;
}

// The joint bilateral upsample of a half-resolution pipeline, guided by the
// full G-buffer so that no AO crosses a silhouette.
PassSpec upsamplePass() {
    return {"upsample", "upsample_bilateral", {"ao_half_blur", "position_half", "position", "normal", "normal_half"}, {"ao_blur"}, false};
}

// A kernel that packs AO with its depth key ("ao_key") is blurred by the
// separable pair, which reads only that.
void separableTail(const kernels::KernelDecl& k, const std::vector<ImageRef>& in, bool half, std::vector<PassSpec>& p) {
    p.push_back({"ao", k.name, in, {"ao", "ao_key"}, half});
    p.push_back({"blur_x", "blur_separable_x", {"ao_key"}, {"ao_key_x"}, half});
    if (half) {
        p.push_back({"blur_y", "blur_separable_y", {"ao_key_x"}, {"ao_half_blur"}, true});
        p.push_back(upsamplePass());
    } else {
        p.push_back({"blur_y", "blur_separable_y", {"ao_key_x"}, {"ao_blur"}, false});
    }
}

// The other kernels by the 2-D bilateral. The hemisphere kernel's 4x4
// rotation tile is cancelled first by a box blur of exactly one tile period
// (the hemisphere SSAO lesson's); with depth_aware_box, blur_box_depth keeps
// the box to one surface so that no silhouette's AO spreads onto the wall
// behind it.
void bilateralTail(const kernels::KernelDecl& k, const RunConfig& c, const std::vector<ImageRef>& in, bool half,
                   std::vector<PassSpec>& p) {
    const std::string suffix = half ? "_half" : "";
    const std::string position = "position" + suffix, normal = "normal" + suffix;
    p.push_back({"ao", k.name, in, {"ao"}, half});
    std::string raw = "ao";
    for (const auto& i : k.inputs)
        if (i.name == "noise4x4") {
            const auto v = kernels::withDefaults(k, c.params);
            if (v.count("depth_aware_box") && v.at("depth_aware_box") != 0)
                p.push_back({"box", "blur_box_depth", {"ao", "depth" + suffix, normal}, {"ao_box"}, half});
            else
                p.push_back({"box", "blur_box", {"ao"}, {"ao_box"}, half});
            raw = "ao_box";
        }
    p.push_back({"blur", "blur_bilateral", {raw, position, normal}, {half ? "ao_half_blur" : "ao_blur"}, half});
    if (half) p.push_back(upsamplePass());
}

}  // namespace

std::vector<PassSpec> buildPasses(const RunConfig& c) {
    const auto* k = kernels::find(c.kernel);
    std::vector<PassSpec> p;
    // An imported G-buffer is uploaded once by PassChain::create: no pass, so
    // nothing is timed for it.
    if (!c.imported())
        p.push_back({"gbuffer", c.raster ? "gbuffer_raster" : "gbuffer_sdf", {}, {"position", "normal", "albedo", "linear_depth"}, false});
    if (!k) return p;
    if (isSsdo(*k)) {
        ssdoPasses(*k, c, p);
        return p;
    }
    // Half resolution: a depth-aware 2x2 downsample of the G-buffer, AO and
    // blur at half size, then the bilateral upsample (Alchemy's reason: a
    // plain upsample leaves halos at silhouettes).
    const bool half = c.half && supportsHalf(c.kernel);
    if (half && downsampleBuildsPyramid(*k, c))
        p.push_back({"downsample", "downsample_pyramid", {"position", "normal"}, {"position_half", "normal_half", "zmip_half"}, true});
    else if (half)
        p.push_back({"downsample", "downsample_depth", {"position", "normal"},
                     {"position_half", "normal_half", "linear_depth_half"}, true});
    const auto in = aoInputs(*k, c, half, p);
    if (packsKey(*k)) separableTail(*k, in, half, p);
    else bilateralTail(*k, c, in, half, p);
    // fused_tail: the upsample and the composite as one pass, which writes
    // the full-resolution AO as well for the gate and the quality measure.
    if (half && c.params.count("fused_tail") && c.params.at("fused_tail") != 0) {
        PassSpec& upsample = p.back();
        upsample.name = "upsample_composite";
        upsample.kernel = "upsample_composite";
        upsample.inputs.push_back(ImageRef{"albedo"});
        upsample.outputs = {"color", "ao_blur"};
        return p;
    }
    p.push_back({"composite", "composite", {"ao_blur", "normal", "albedo"}, {"color"}, false});
    return p;
}

std::vector<OutputSpec> userOutputs(const RunConfig& c) {
    return {{"ao", c.half && supportsHalf(c.kernel) ? "raw ambient occlusion (half resolution)" : "raw ambient occlusion"},
            {"ao_blur", "blurred ambient occlusion"},
            {"color", "composited image"},
            {"normal", "G-buffer view-space normal"}};
}

Status validate(const RunConfig& c) {
    const auto* k = kernels::find(c.kernel);
    // "reference" kernels (the ground truth) run in the AO slot when named;
    // sweeps over "every AO kernel" leave them out (they are slow by design).
    if (!k || (k->role != kernels::Role::Ao && k->role != kernels::Role::Reference)) return badInput("--kernel " + c.kernel + ": unknown kernel (have: " + aoKernelNames() +
                        "; a package's: load it with --kernels DIR or CAVITY_KERNELS)");
    if (c.width < 1 || c.height < 1 || c.width > kMaxResolution || c.height > kMaxResolution)
        return badInput("--res " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                        ": must be WIDTHxHEIGHT with each in 1.." + std::to_string(kMaxResolution));
    if (c.raster && c.imported()) return badInput("--gbuffer: raster and import exclude each other");
    // A pass that evaluates the analytic scene itself has no scene to
    // evaluate when the G-buffer is a capture.
    if (c.imported())
        for (const auto& spec : buildPasses(c))
            if (const auto* d = kernels::find(spec.kernel); d && kernels::evaluatesScene(*d))
                return badInput("--kernel " + c.kernel + ": pass " + spec.name + " (" + d->name +
                                        ") evaluates the analytic scene, so it cannot run on an imported G-buffer "
                                        "(--gbuffer import); use a screen-space kernel (have: " + screenSpaceAoNames() + ")");
    if (c.half && !supportsHalf(c.kernel))
        return badInput("--resolution half: kernel " + c.kernel + " has no half-resolution pipeline (use full)");
    if (interleaveOf(c) > 1 && pyramidPerLevel(c))
        return badInput("--pyramid_per_level 1: the interleaved layers (--interleave " + std::to_string(interleaveOf(c)) +
                        ") are written by the one-dispatch pyramid; use one or the other");
    // A pass that writes a mip chain needs a level for each: an image of at
    // least 2^(levels - 1) px on its longer side, found here rather than as
    // the API's error when the image is made.
    for (const auto& spec : buildPasses(c)) {
        const auto* d = kernels::find(spec.kernel);
        if (!d) continue;
        for (const auto& o : d->outputs) {
            const int need = 1 << (o.mipLevels - 1);
            const int w = spec.half ? (c.width + 1) / 2 : c.width, h = spec.half ? (c.height + 1) / 2 : c.height;
            if (std::max(w, h) >= need) continue;
            return badInput("--res " + std::to_string(c.width) + "x" + std::to_string(c.height) + ": pass " + spec.name +
                            " of " + c.kernel + " writes " + std::to_string(o.mipLevels) +
                            " mip levels, which need at least " + std::to_string(spec.half ? 2 * need - 1 : need) +
                            " px on the longer side" + (spec.half ? " at --resolution half" : ""));
        }
    }
    // Values set in code (sweeps, matrices, tests) rather than parsed.
    for (const auto& [name, v] : c.params) {
        const auto* p = kernels::findParam(name);
        if (!p) return badInput("--" + name + ": unknown flag");
        CAVITY_TRY(kernels::checkValue(*p, v));
    }
    return {};
}

}  // namespace cavity::pipeline