#include "plan/sweep.h"

#include "plan/axes.h"

#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <set>

namespace cavity::plan {

SweepAxes gpuSweep() { return {}; }

SweepAxes cpuSweep() {
    SweepAxes a;
    a.samples = {4, 16, 64};
    a.blurs = {0, 4};
    a.sizes = {{320, 180}};
    a.defaultSize = {320, 180};
    a.product = false;
    a.fragmentAxes = false;
    return a;
}

std::vector<std::string> aoKernels() {
    std::vector<std::string> names;
    for (const auto& k : kernels::all())
        if (k.role == kernels::Role::Ao) names.push_back(k.name);
    return names;
}

namespace {

// The SDF AO family: the kernels that evaluate the scene themselves.
bool sdfFamily(const std::string& kernel) {
    const auto* k = kernels::find(kernel);
    return k && kernels::evaluatesScene(*k);
}

bool declares(const std::string& kernel, const std::string& param) {
    const auto* k = kernels::find(kernel);
    return k && kernels::declares(*k, param);
}

bool readsPyramid(const std::string& kernel) {
    const auto* k = kernels::find(kernel);
    return k && std::any_of(k->inputs.begin(), k->inputs.end(), [](const auto& i) { return i.name == "zmip"; });
}

}  // namespace

std::vector<RunConfig> benchmarkSweep(const SweepAxes& axes, const std::vector<gpu::Api>& apis) {
    std::vector<RunConfig> out;
    std::set<std::string> seen;
    auto add = [&](const Axes& a, const RunConfig& base) {
        auto configs = expandAxes(a, base);
        if (!configs) return;   // no scene axis here: nothing can fail
        for (auto& c : *configs)
            if (seen.insert(configId(c)).second) out.push_back(std::move(c));
    };
    const std::vector<double> samples(axes.samples.begin(), axes.samples.end()), blurs(axes.blurs.begin(), axes.blurs.end());
    // Axes of parameters and full/half; every other axis at the base's value.
    auto around = [](std::vector<std::pair<std::string, std::vector<double>>> params, std::vector<bool> half = {}) {
        Axes a;
        a.params = std::move(params);
        a.half = std::move(half);
        return a;
    };
    Axes sizes;
    sizes.sizes = axes.sizes;
    for (const auto& kernel : aoKernels())
        for (auto api : apis)
            for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
                RunConfig base;
                base.kernel = kernel;
                base.api = api;
                base.stage = stage;
                std::tie(base.width, base.height) = axes.defaultSize;
                add(Axes{}, base);
                if (stage == gpu::Stage::Fragment && (!axes.fragmentAxes || sdfFamily(kernel))) continue;
                // One axis at a time around the default configuration.
                add(around({{"samples", samples}}), base);
                add(around({{"blur", blurs}}), base);
                add(around({}, {true}), base);
                add(sizes, base);
                if (!axes.product || stage != gpu::Stage::Compute) continue;
                // The SDF family shares the blur, so its product is samples x
                // full/half at the default blur: enough for the quality-cost
                // chart's every kernel x sample count x full/half.
                if (sdfFamily(kernel)) add(around({{"samples", samples}}, {true}), base);
                else add(around({{"samples", samples}, {"blur", blurs}}, {false, true}), base);
                // The fused half-resolution tail against the two passes, at
                // the default samples and blur.
                if (pipeline::supportsHalf(kernel) && !sdfFamily(kernel))
                    add(around({{"fused_tail", {1}}}, {true}), base);
                // The precision contract's other side, where a kernel offers it.
                if (declares(kernel, "exact")) add(around({{"exact", {1}}}), base);
                // The depth pyramid a dispatch per level, against the one dispatch.
                if (readsPyramid(kernel)) add(around({{"pyramid_per_level", {1}}}), base);
                // Interleaved layers against the plain dispatch, full and
                // half, at the samples the AO pass's targets name.
                if (declares(kernel, "interleave"))
                    add(around({{"interleave", {4}}, {"samples", {16, 32}}}, {false, true}), base);
            }
    return out;
}

}  // namespace cavity::plan