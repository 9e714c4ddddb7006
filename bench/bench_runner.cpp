#include "bench_runner.h"

#include "kernel.h"
#include "pipeline.h"
#include "sweep.h"
#include "timing.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>

namespace cavity::bench {

namespace {

std::map<gpu::Api, std::unique_ptr<gpu::Backend>>& backends() {
    static std::map<gpu::Api, std::unique_ptr<gpu::Backend>> b;
    return b;
}

// Per-pixel cost model, shared with the roofline note (bench/ROOFLINE.md).
double bytesPerPixel(const PassSpec& p, const RunConfig& c) {
    const auto* k = kernels::find(p.kernel);
    return k && k->cost ? k->cost(kernels::withDefaults(*k, c.params)).bytesPerPixel : 0.0;
}

double aoSamplesPerPixel(const PassSpec& p, const RunConfig& c) {
    const auto* k = kernels::find(p.kernel);
    return k && k->role == "ao" ? double(c.samples()) : 0.0;
}

struct Bench {
    RunConfig config;
    int iterations, warmup;
};

void run(benchmark::State& state, const Bench& b) {
    gpu::Backend& gpu = *backends().at(b.config.api);
    // Four camera views of the scene, used in turn, so that no iteration
    // reads inputs the previous one left in the caches.
    std::vector<std::unique_ptr<PassChain>> chains;
    for (int view = 0; view < 4; ++view) {
        RunConfig c = b.config;
        c.params["view"] = view;
        auto chain = PassChain::create(gpu, c);
        if (!chain) {
            state.SkipWithError(chain.error().message.c_str());
            return;
        }
        chains.push_back(std::move(*chain));
    }
    // Which clock brackets the work on this backend: decided on the first chain.
    auto probe = measure(gpu, *chains[0], b.warmup, 3);
    if (!probe) {
        state.SkipWithError(probe.error().message.c_str());
        return;
    }
    const bool wall = probe->clock == "wall";
    const auto& passes = chains[0]->passes();
    std::vector<std::vector<double>> passMs(passes.size());
    size_t turn = 0;
    for (auto _ : state) {
        PassChain& chain = *chains[turn++ % chains.size()];
        double aoMs = 0;
        if (!wall) {
            gpu.beginFrame();
            chain.record();
            if (auto s = gpu.endFrame(); !s) {
                state.SkipWithError(s.error().message.c_str());
                return;
            }
            const auto t = gpu.scopeTimes();
            for (size_t i = 0; i < passes.size() && i < t.size(); ++i) {
                passMs[i].push_back(t[i].gpuMs);
                if (passes[i].name != "gbuffer") aoMs += t[i].gpuMs;
            }
        } else {
            for (size_t i = 0; i < passes.size(); ++i) {
                (void)gpu.finish();
                const auto t0 = std::chrono::steady_clock::now();
                gpu.beginFrame();
                chain.recordPass(i);
                if (auto s = gpu.endFrame(); !s) {
                    state.SkipWithError(s.error().message.c_str());
                    return;
                }
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                passMs[i].push_back(ms);
                if (passes[i].name != "gbuffer") aoMs += ms;
            }
        }
        state.SetIterationTime(aoMs / 1000.0);
    }
    const RunConfig& c = b.config;
    double pixels = 0, samples = 0, bytes = 0;
    for (size_t i = 0; i < passes.size(); ++i) {
        if (passes[i].name == "gbuffer") continue;
        const double px = double(chains[0]->passPixels(i));
        samples += px * aoSamplesPerPixel(passes[i], c);
        bytes += px * bytesPerPixel(passes[i], c);
        state.counters["pass_" + passes[i].name + "_ms"] = summarize(passMs[i]).median;
    }
    pixels = double(c.width) * c.height;
    using benchmark::Counter;
    state.counters["MP/s"] = Counter(pixels / 1e6, Counter::kIsIterationInvariantRate);
    state.counters["samples/s"] = Counter(samples, Counter::kIsIterationInvariantRate);
    state.counters["bytes/s"] = Counter(bytes, Counter::kIsIterationInvariantRate, Counter::kIs1024);
    state.counters["width"] = c.width;
    state.counters["height"] = c.height;
    state.counters["samples"] = c.samples();
    state.counters["blur"] = c.blur();
    state.counters["half"] = c.half;
    state.counters["fragment"] = c.stage == gpu::Stage::Fragment;
    state.SetLabel(wall ? "clock=wall (timestamps do not bracket the work)" : "clock=gpu-timestamp");
}

// What an empty timestamp pair reads: the floor under every pass time.
void emptyScope(benchmark::State& state, gpu::Api api) {
    gpu::Backend& gpu = *backends().at(api);
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

}  // namespace

Result<int> registerSweep(const Options& o) {
    std::vector<gpu::Api> apis;
    if (o.backend == "gl" || o.backend == "all") apis.push_back(gpu::Api::OpenGL);
    if (o.backend == "vk" || o.backend == "all") apis.push_back(gpu::Api::Vulkan);
    if (apis.empty()) return badInput("--backend " + o.backend + ": must be gl, vk or all");
    if (o.sweep != "gpu" && o.sweep != "cpu" && o.sweep != "auto")
        return badInput("--sweep " + o.sweep + ": must be gpu, cpu or auto");
    std::vector<gpu::Api> started;
    bool allSoftware = true;
    std::string devices, drivers, versions;
    for (auto api : apis) {
        gpu::BackendOptions bo;
        bo.deviceIndex = o.device;
        auto b = gpu::createBackend(api, bo);
        if (!b) {
            std::cerr << "cavity_bench: " << b.error().message << " (skipping " << gpu::apiName(api) << ")\n";
            continue;
        }
        const auto& info = (*b)->info();
        allSoftware &= info.softwareRenderer;
        const std::string tag = std::string(gpu::apiName(api)) + ": ";
        devices += (devices.empty() ? "" : "; ") + tag + info.deviceName;
        drivers += (drivers.empty() ? "" : "; ") + tag + info.driver;
        versions += (versions.empty() ? "" : "; ") + tag + info.apiVersion;
        backends()[api] = std::move(*b);
        started.push_back(api);
    }
    if (started.empty()) return unavailable("no backend could start");
    const bool cpu = o.sweep == "cpu" || (o.sweep == "auto" && allSoftware);
    benchmark::AddCustomContext("cavity_device", devices);
    benchmark::AddCustomContext("cavity_driver", drivers);
    benchmark::AddCustomContext("cavity_api_versions", versions);
    benchmark::AddCustomContext("cavity_software_renderer", allSoftware ? "true" : "false");
    benchmark::AddCustomContext("cavity_sweep", cpu ? "cpu" : "gpu");
    if (const char* clocks = std::getenv("CAVITY_GPU_CLOCKS")) benchmark::AddCustomContext("cavity_gpu_clocks", clocks);
    const int iterations = o.iterations > 0 ? o.iterations : (cpu ? 5 : 50);
    const int warmup = o.warmup > 0 ? o.warmup : (cpu ? 1 : 5);
    const auto configs = benchmarkSweep(cpu ? cpuSweep() : gpuSweep(), started);
    for (const auto& c : configs) {
        Bench b{c, iterations, warmup};
        benchmark::RegisterBenchmark(configId(c).c_str(), [b](benchmark::State& s) { run(s, b); })
            ->UseManualTime()
            ->Iterations(iterations)
            ->Unit(benchmark::kMillisecond);
    }
    for (auto api : started)
        benchmark::RegisterBenchmark((std::string("timer/empty_scope/") + gpu::apiName(api)).c_str(),
                                     [api](benchmark::State& s) { emptyScope(s, api); })
            ->UseManualTime()
            ->Iterations(iterations)
            ->Unit(benchmark::kMicrosecond);
    return int(configs.size() + started.size());
}

void releaseBackends() { backends().clear(); }

}  // namespace cavity::bench
