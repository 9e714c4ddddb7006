#include "plan/sweep.h"

#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"

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

}  // namespace

std::vector<RunConfig> benchmarkSweep(const SweepAxes& axes, const std::vector<gpu::Api>& apis) {
    std::vector<RunConfig> out;
    std::set<std::string> seen;
    auto add = [&](RunConfig c) {
        if (c.half && !supportsHalf(c.kernel)) return;
        if (seen.insert(configId(c)).second) out.push_back(std::move(c));
    };
    for (const auto& kernel : aoKernels())
        for (auto api : apis)
            for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
                RunConfig base;
                base.kernel = kernel;
                base.api = api;
                base.stage = stage;
                base.width = axes.defaultSize.first;
                base.height = axes.defaultSize.second;
                add(base);
                if (stage == gpu::Stage::Fragment && (!axes.fragmentAxes || sdfFamily(kernel))) continue;
                for (int n : axes.samples) {
                    RunConfig c = base;
                    c.params["samples"] = n;
                    add(c);
                }
                for (int b : axes.blurs) {
                    RunConfig c = base;
                    c.params["blur"] = b;
                    add(c);
                }
                {
                    RunConfig c = base;
                    c.half = true;
                    add(c);
                }
                for (auto [w, h] : axes.sizes) {
                    RunConfig c = base;
                    c.width = w;
                    c.height = h;
                    add(c);
                }
                // The SDF family shares the blur, so its product is samples x
                // full/half at the default blur: enough for the quality-cost
                // chart's every kernel x sample count x full/half.
                if (axes.product && stage == gpu::Stage::Compute && sdfFamily(kernel))
                    for (int n : axes.samples) {
                        RunConfig c = base;
                        c.params["samples"] = n;
                        c.half = true;
                        add(c);
                    }
                if (axes.product && stage == gpu::Stage::Compute && !sdfFamily(kernel))
                    for (int n : axes.samples)
                        for (int b : axes.blurs)
                            for (bool half : {false, true}) {
                                RunConfig c = base;
                                c.params["samples"] = n;
                                c.params["blur"] = b;
                                c.half = half;
                                add(c);
                            }
            }
    return out;
}

}  // namespace cavity::plan