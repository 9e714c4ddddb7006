#include "bench_runner.h"
#include "overhead_probes.h"

#include "pipeline/config_id.h"
#include "kernel.h"
#include "pipeline/pipeline.h"
#include "plan/sweep.h"
#include "measure/gpu_clocks.h"
#include "measure/roofline.h"
#include "measure/timing.h"
#include "measure/results.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <memory>

namespace cavity::bench {

namespace {

std::map<gpu::Api, std::unique_ptr<gpu::Backend>>& backends() {
    static std::map<gpu::Api, std::unique_ptr<gpu::Backend>> b;
    return b;
}

// Per-pixel cost model, shared with the roofline note (bench/ROOFLINE.md).
double bytesPerPixel(const PassSpec& p, const RunConfig& c, const kernels::PassShape& shape) {
    const auto* k = kernels::find(p.kernel);
    return k && k->cost ? k->cost(kernels::withDefaults(*k, c.params), shape).bytesPerPixel : 0.0;
}

double aoSamplesPerPixel(const PassSpec& p, const RunConfig& c) {
    const auto* k = kernels::find(p.kernel);
    return k && k->role == kernels::Role::Ao ? double(c.samples()) : 0.0;
}

struct Bench {
    RunConfig config;
    TimingOptions timing;
    PlantedSlowdown plant;
    SourceOverrides overrides;
};

// The clock of each configuration, decided by its first repetition and kept
// by the others, so that one configuration's repetitions are all on GPU
// timestamps or all on the wall clock, never a mix.
std::map<std::string, std::string>& configurationClocks() {
    static std::map<std::string, std::string> clocks;
    return clocks;
}

// Each pass's floor and its median over it; no counters where the
// pass has no floor (results.json's floor_reason says why).
void setFloorCounters(benchmark::State& state, const gpu::Backend& gpu, const PassChain& chain, const RunConfig& c,
                      const Timing& t) {
    const auto& passes = chain.passes();
    const GpuClocks* gpuClocks = GpuClocks::forDevice(gpu.info());
    const DeviceFloor device = deviceFloor(gpu.info(), gpuClocks ? gpuClocks->maxSmMhz() : std::nullopt);
    for (size_t i = 0; i < passes.size(); ++i) {
        const auto f =
            passFloor(device, passes[i].kernel, c.params, double(chain.passPixels(i)), chain.passShape(i), c.api);
        if (!f.floor) continue;
        state.counters["floor_" + passes[i].name + "_ms"] = f.floor->ms();
        state.counters["over_floor_" + passes[i].name] = t.passes[i].stats.median / f.floor->ms();
    }
}

// Each pass's register count where the driver reports one (gpu::registerCount).
void setRegisterCounters(benchmark::State& state, const PassChain& chain) {
    for (const auto& [pass, info] : chain.pipelineInfos())
        if (const double n = gpu::registerCount(info.stats); n >= 0) state.counters["registers_" + pass] = n;
}

// Each pass's median, the AO pipeline's throughput, and the configuration.
void setWorkCounters(benchmark::State& state, const PassChain& chain, const RunConfig& c, const Timing& t) {
    const auto& passes = chain.passes();
    double pixels = 0, samples = 0, bytes = 0;
    for (size_t i = 0; i < passes.size(); ++i) {
        if (passes[i].name == "gbuffer") {
            state.counters["pass_gbuffer_ms"] = t.passes[i].stats.median;
            continue;
        }
        const double px = double(chain.passPixels(i));
        samples += px * aoSamplesPerPixel(passes[i], c);
        bytes += px * bytesPerPixel(passes[i], c, chain.passShape(i));
        state.counters["pass_" + passes[i].name + "_ms"] = t.passes[i].stats.median;
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
}

// How this repetition was measured, and at which clocks.
void setTimingCounters(benchmark::State& state, const Timing& t) {
    state.counters["frames"] = double(t.frame.ms.size());
    state.counters["batch_frames"] = t.batchFrames;
    state.counters["noise_pct"] = std::isfinite(t.noise) ? 100.0 * t.noise : -1.0;
    state.counters["rejected_frames"] = t.rejectedFrames;
    state.counters["warmup_s"] = t.warmupSeconds;
    if (!t.clocks.source.empty()) {
        state.counters["sm_mhz_min"] = t.clocks.smMin;
        state.counters["sm_mhz_median"] = t.clocks.smMedian;
        state.counters["sm_mhz_max"] = t.clocks.smMax;
        state.counters["mem_mhz_median"] = t.clocks.memMedian;
    }
    std::string label = "clock=" + t.clock + " mode=" + timingModeName(t.mode) + " stop=" + t.stop;
    if (t.steadyChecked && !t.steady) label += " unsteady-warmup";
    if (t.clocks.moved()) label += " sm-clock-moved";
    // How the clock was decided, where it was not simply on the first warm check.
    if (t.clockNote.find("re-decided") != std::string::npos) label += " clock-re-decided";
    else if (t.clock == "gpu-timestamp" && t.clockNote.find("the cold probe before warm-up had said") != std::string::npos)
        label += " cold-probe-overruled";
    if (t.rejectedFrames) label += " rejected=" + std::to_string(t.rejectedFrames);
    state.SetLabel(label);
}

// The pipeline timed as one scope (PassChain::recordInOneScope), the median
// of kOneScopeFrames frames each its own submission, on the chain the
// measurement has just warmed: "pipeline_one_scope_ms", beside the sum of
// the passes' own scopes, which carries a timestamp pair a pass. Only where
// the timestamps are the clock; nothing where a frame fails.
void setOneScopeCounter(benchmark::State& state, gpu::Backend& gpu, PassChain& chain, const Timing& t) {
    constexpr int kOneScopeFrames = 21;
    if (t.clock != "gpu-timestamp") return;
    std::vector<double> ms;
    for (int f = 0; f < kOneScopeFrames; ++f) {
        gpu.beginFrame();
        chain.recordInOneScope();
        if (!gpu.endFrame()) return;
        for (const auto& s : gpu.scopeTimes())
            if (s.name == "pipeline") ms.push_back(s.gpuMs);
    }
    if (!ms.empty()) state.counters["pipeline_one_scope_ms"] = stats::summarize(ms).median;
}

// One benchmark iteration is one whole measurement (harness/measure/timing.h: batched
// frames after a steady warm-up, stopped on noise), so every Google Benchmark
// repetition is an independent measurement and the repetitions' spread is the
// run-to-run noise a comparison has to beat.
void run(benchmark::State& state, const Bench& b) {
    gpu::Backend& gpu = *backends().at(b.config.api);
    const std::string id = configId(b.config);
    // Four camera views of the scene, used in turn, so that no frame reads
    // inputs the previous one left in the caches.
    std::vector<std::unique_ptr<PassChain>> chains;
    std::vector<PassChain*> views;
    for (int view = 0; view < 4; ++view) {
        RunConfig c = b.config;
        c.params["view"] = view;
        auto chain = PassChain::create(gpu, c, b.overrides, b.plant);
        if (!chain) {
            noteFailure(id, chain.error());
            state.SkipWithError(chain.error().message.c_str());
            return;
        }
        chains.push_back(std::move(*chain));
        views.push_back(chains.back().get());
    }
    TimingOptions options = b.timing;
    auto& clocks = configurationClocks();
    if (auto it = clocks.find(id); it != clocks.end()) options.clock = it->second;
    Timing t;
    for (auto _ : state) {
        auto m = measurePasses(gpu, views, options, GpuClocks::forDevice(gpu.info()));
        if (!m) {
            noteFailure(id, m.error());
            state.SkipWithError(m.error().message.c_str());
            return;
        }
        t = std::move(*m);
        clocks.emplace(id, t.clock);
        // The benchmark's time: the AO pipeline, every pass but the G-buffer, per frame.
        state.SetIterationTime(t.pipeline.stats.median / 1000.0);
    }
    const RunConfig& c = b.config;
    setFloorCounters(state, gpu, *chains[0], c, t);
    setWorkCounters(state, *chains[0], c, t);
    setRegisterCounters(state, *chains[0]);
    setTimingCounters(state, t);
    setOneScopeCounter(state, gpu, *chains[0], t);
}

}  // namespace

// A plant that would plant nothing is an error, never a run that reports "no
// regression": every --plant pass must be a pass of some configuration of
// the sweep, and every --plant-file configuration and pass one of the sweep's.
Status checkPlants(const Options& o, const std::vector<RunConfig>& configs) {
    std::set<std::string> allPasses;
    std::map<std::string, std::set<std::string>> byId;
    for (const auto& c : configs)
        for (const auto& p : buildPasses(c)) {
            allPasses.insert(p.name);
            byId[configId(c)].insert(p.name);
        }
    auto list = [](const std::set<std::string>& names) {
        std::string out;
        for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
        return out;
    };
    for (const auto& [pass, fmas] : o.plant)
        if (!allPasses.count(pass))
            return badInput("--plant " + pass + ":" + std::to_string(fmas) + ": no configuration of the sweep has a pass '" +
                            pass + "' (passes: " + list(allPasses) + ")");
    for (const auto& [id, plant] : o.plantById) {
        const auto c = byId.find(id);
        if (c == byId.end())
            return badInput("--plant-file: configuration '" + id + "' is not in the sweep (see --benchmark_list_tests)");
        for (const auto& [pass, fmas] : plant)
            if (!c->second.count(pass))
                return badInput("--plant-file: " + id + " has no pass '" + pass + "' (passes: " + list(c->second) + ")");
    }
    return {};
}

// The configurations Google Benchmark's filter runs: a std::regex search of
// the name it registers (the id, then /iterations:1/manual_time), extended,
// '-' first negating it, as it applies it.
std::vector<RunConfig> selected(const std::vector<RunConfig>& configs, const std::string& filter) {
    if (filter.empty() || filter == "all" || filter == ".") return configs;
    const bool negate = filter[0] == '-';
    const std::regex re(negate ? filter.substr(1) : filter, std::regex_constants::extended);
    std::vector<RunConfig> out;
    for (const auto& c : configs)
        if (std::regex_search(configId(c) + "/iterations:1/manual_time", re) != negate) out.push_back(c);
    return out;
}

// What the run changed on purpose, beside its numbers: a planted slowdown,
// edited kernels; and which packages from disk its kernels came from.
void addEditContext(const Options& o) {
    if (!o.plant.empty() || !o.plantById.empty()) {
        std::string text;
        for (const auto& [pass, fmas] : o.plant) text += (text.empty() ? "" : ",") + pass + ":" + std::to_string(fmas);
        if (!o.plantById.empty()) text += (text.empty() ? "" : "; ") + std::to_string(o.plantById.size()) + " configurations from --plant-file";
        benchmark::AddCustomContext("cavity_planted_slowdown", text);
    }
    if (!o.replaced.empty()) {
        std::string text;
        for (const auto& r : o.replaced) text += (text.empty() ? "" : "; ") + r.name + "=" + r.file + " (" + r.digest + ")";
        benchmark::AddCustomContext("cavity_kernel_sources", text);
    }
    std::string text;
    for (const auto& p : measure::packagesLoaded()) text += (text.empty() ? "" : "; ") + p.name + "=" + p.folder + " (" + p.digest + ")";
    if (!text.empty()) benchmark::AddCustomContext("cavity_kernel_packages", text);
}

Result<int> registerSweep(const Options& o) {
    std::vector<gpu::Api> apis;
    if (o.backend == "gl" || o.backend == "all") apis.push_back(gpu::Api::OpenGL);
    if (o.backend == "vk" || o.backend == "all") apis.push_back(gpu::Api::Vulkan);
    if (apis.empty()) return badInput("--backend " + o.backend + ": must be gl, vk or all");
    if (o.sweep != "gpu" && o.sweep != "cpu" && o.sweep != "auto")
        return badInput("--sweep " + o.sweep + ": must be gpu, cpu or auto");
    std::vector<gpu::Api> started;
    bool allSoftware = true;
    std::string devices, drivers, versions, floors;
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
        const GpuClocks* clocks = GpuClocks::forDevice(info);
        floors += (floors.empty() ? "" : "; ") + tag + describe(deviceFloor(info, clocks ? clocks->maxSmMhz() : std::nullopt));
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
    benchmark::AddCustomContext("cavity_floor_device", floors);
    benchmark::AddCustomContext("cavity_sweep", cpu ? "cpu" : "gpu");
    // A timing diagnostic changes every number: say so beside them.
    for (const char* name : {"CAVITY_FULL_BARRIERS", "CAVITY_NO_BARRIERS", "CAVITY_WORKGROUP"})
        if (const char* v = std::getenv(name); v && *v && std::string(v) != "0")
            benchmark::AddCustomContext(std::string("cavity_env_") + name, v);
    if (const char* clocks = std::getenv("CAVITY_GPU_CLOCKS")) benchmark::AddCustomContext("cavity_gpu_clocks", clocks);
    // The timing options of the first backend's device (both APIs run on one device).
    TimingOptions timing = defaultTimingOptions(backends().at(started[0])->info());
    if (cpu) {
        timing.frames = 5;
        timing.warmup = 1;
    }
    if (o.frames) timing.frames = *o.frames;
    if (o.warmup) timing.warmup = *o.warmup;
    if (o.mode) timing.mode = *o.mode;
    if (o.maxNoise) timing.maxNoise = *o.maxNoise;
    if (o.maxSeconds) timing.maxSeconds = *o.maxSeconds;
    benchmark::AddCustomContext("cavity_timing_mode", timingModeName(timing.mode));
    benchmark::AddCustomContext("cavity_timing",
                                "min_frames=" + std::to_string(timing.frames) + " warmup=" + std::to_string(timing.warmup) +
                                    (timing.steadyWarmup ? "+steady" : "") + " max_noise=" +
                                    std::to_string(timing.maxNoise) + " max_seconds=" + std::to_string(timing.maxSeconds));
    const auto configs = benchmarkSweep(cpu ? cpuSweep() : gpuSweep(), started);
    CAVITY_TRY(checkPlants(o, configs));
    CAVITY_TRY(checkSourcesUsed(o.replaced, selected(configs, o.filter)));
    addEditContext(o);
    for (const auto& c : configs) {
        const auto planted = o.plantById.find(configId(c));
        Bench b{c, timing, planted == o.plantById.end() ? o.plant : planted->second, o.overrides};
        benchmark::RegisterBenchmark(configId(c).c_str(), [b](benchmark::State& s) { run(s, b); })
            ->UseManualTime()
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
    }
    // The probes at the sweep's largest size: 1920x1080 on a GPU.
    int probes = 0;
    for (auto api : started) probes += registerOverheadProbes(*backends().at(api), api, cpu ? 320 : 1920, cpu ? 180 : 1080);
    return int(configs.size()) + probes;
}

void releaseBackends() { backends().clear(); }

namespace {
std::vector<Failure>& failureList() {
    static std::vector<Failure> list;
    return list;
}
}  // namespace

void noteFailure(const std::string& id, const Error& error) {
    static std::mutex m;
    const std::lock_guard<std::mutex> lock(m);
    failureList().push_back({id, error});
}

const std::vector<Failure>& failures() { return failureList(); }

}  // namespace cavity::bench
