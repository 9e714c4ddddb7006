#include "overhead_probes.h"

#include "kernel.h"
#include "measure/timing.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

namespace cavity::bench {

namespace {

using stats::summarize;

constexpr int kChainPasses = 8;
const kernels::Workgroup kGroup;   // the compute passes' own shape (kernels/kernel.h)

// A pass that launches its workgroups and does nothing, or stores one RGBA8
// texel per invocation into its own image: no pass reads another's image, so
// the chain needs no barrier, and any time a barrier adds is its own cost.
gpu::ComputePipelineDesc probeKernel(bool store) {
    gpu::ComputePipelineDesc d;
    const std::string size = "layout(local_size_x = " + std::to_string(kGroup.x) + ", local_size_y = " +
                             std::to_string(kGroup.y) + ") in;\n";
    d.shader = {store ? "probe_store" : "probe_empty", gpu::Stage::Compute,
                "#version 450\n" + size +
                    (store ? "layout(binding = 0, rgba8) uniform writeonly image2D o;\n"
                             "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                             "  if (all(lessThan(p, imageSize(o)))) imageStore(o, p, vec4(0.25, 0.5, 0.75, 1.0)); }\n"
                           : "void main() {}\n"),
                {"<overhead probe>"}};
    if (store) d.layout = {{0, gpu::BindingKind::StorageImage, gpu::Format::RGBA8}};
    d.localSizeX = int(kGroup.x);
    d.localSizeY = int(kGroup.y);
    d.label = d.shader.name;
    return d;
}

// What an empty timestamp pair reads: the floor under every pass time.
void emptyScope(benchmark::State& state, gpu::Backend& gpu) {
    std::vector<double> ms;
    for (auto _ : state) {
        gpu.beginFrame();
        gpu.beginScope("empty");
        gpu.endScope();
        if (auto s = gpu.endFrame(); !s) {
            state.SkipWithError(s.error().message.c_str());
            return;
        }
        const double t = gpu.scopeTimes().at(0).gpuMs;
        ms.push_back(t);
        state.SetIterationTime(t / 1000.0);
    }
    state.counters["median_us"] = 1000.0 * summarize(ms).median;
}

// kChainPasses dispatches of width x height, each in its own scope with a
// barrier() between them. The iteration's time is one pass's, the median
// over the chain's passes after the first; the first is reported apart,
// since it also waits for whatever the frame's start leaves. `oneScope`:
// the passes after the first share one scope, and a pass's time is its
// share of it: what a pass costs without timestamps of its own.
void chain(benchmark::State& state, gpu::Backend& gpu, bool store, int width, int height, bool oneScope = false) {
    auto pipe = gpu.createComputePipeline(probeKernel(store));
    if (!pipe) {
        state.SkipWithError(pipe.error().message.c_str());
        return;
    }
    std::vector<gpu::Image> images;
    std::vector<std::vector<gpu::Bind>> binds(kChainPasses);   // each pass's own image, or nothing
    auto release = [&] {
        for (auto img : images) gpu.destroy(img);
        gpu.destroy(*pipe);
    };
    for (int i = 0; store && i < kChainPasses; ++i) {
        auto img = gpu.createImage({width, height, gpu::Format::RGBA8, 1, "probe_" + std::to_string(i)});
        if (!img) {
            state.SkipWithError(img.error().message.c_str());
            release();
            return;
        }
        images.push_back(*img);
        binds[size_t(i)] = {{0, *img, {}, {}, 0}};
    }
    std::vector<double> later, first;
    for (auto _ : state) {
        gpu.beginFrame();
        for (int i = 0; i < kChainPasses; ++i) {
            if (i) gpu.barrier();
            if (!oneScope || i < 2) gpu.beginScope(i ? "passes" : "pass");
            gpu.dispatch(*pipe, binds[size_t(i)], kGroup.groupsX(width), kGroup.groupsY(height));
            if (!oneScope || i == 0 || i == kChainPasses - 1) gpu.endScope();
        }
        if (auto s = gpu.endFrame(); !s) {
            state.SkipWithError(s.error().message.c_str());
            break;
        }
        const auto scopes = gpu.scopeTimes();
        std::vector<double> passes;
        for (size_t i = 1; i < scopes.size(); ++i) passes.push_back(scopes[i].gpuMs);
        const double t = oneScope ? scopes.at(1).gpuMs / (kChainPasses - 1) : summarize(passes).median;
        later.push_back(t);
        first.push_back(scopes.at(0).gpuMs);
        state.SetIterationTime(t / 1000.0);
    }
    if (!later.empty()) {
        state.counters["median_us"] = 1000.0 * summarize(later).median;
        state.counters["first_pass_us"] = 1000.0 * summarize(first).median;
        state.counters["width"] = width;
        state.counters["height"] = height;
        state.counters["workgroups"] = double(kGroup.groupsX(width)) * kGroup.groupsY(height);
    }
    release();
}

}  // namespace

int registerOverheadProbes(gpu::Backend& gpu, gpu::Api api, int width, int height) {
    const std::string tag = gpu::apiName(api);
    gpu::Backend* g = &gpu;
    benchmark::RegisterBenchmark(("timer/empty_scope/" + tag).c_str(), [g](benchmark::State& s) { emptyScope(s, *g); })
        ->UseManualTime()
        ->Iterations(50)
        ->Unit(benchmark::kMicrosecond);
    // `oneScope`: the empty chain's passes after the first under one scope.
    auto registerChain = [&](bool store, int w, int h, bool oneScope = false) {
        const std::string kind = store ? "store_chain/" : oneScope ? "empty_chain_one_scope/" : "empty_chain/";
        const std::string id = "timer/" + kind + std::to_string(w) + "x" + std::to_string(h) + "/" + tag;
        benchmark::RegisterBenchmark(id.c_str(),
                                     [g, store, w, h, oneScope](benchmark::State& s) { chain(s, *g, store, w, h, oneScope); })
            ->UseManualTime()
            ->Iterations(50)
            ->Unit(benchmark::kMicrosecond);
    };
    registerChain(false, width, height);
    registerChain(true, width, height);
    registerChain(false, width, height, true);
    // The empty dispatch at sizes from twice the sweep's down to an eighth
    // of it: the launch cost against the number of workgroups, which the
    // floor model's launch term is fitted to (docs/roofline.md).
    for (int shift : {-1, 1, 2, 3}) {
        const int w = shift < 0 ? width * 2 : std::max(1, width >> shift);
        const int h = shift < 0 ? height * 2 : std::max(1, height >> shift);
        registerChain(false, w, h);
    }
    return 8;
}

}  // namespace cavity::bench
