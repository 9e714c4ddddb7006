// The benchmark runner: one Google Benchmark per configuration of the sweep
// (harness/sweep.h), named by its configuration id. Each iteration's time is
// the GPU time of the AO part of the pipeline (every pass but the G-buffer),
// from the backend's timestamps (UseManualTime), or from the drained wall
// clock where the timestamps do not bracket the work (llvmpipe GL). The
// iteration count is fixed, so CPU time never decides how long a GPU
// benchmark runs. Inputs rotate among four camera views of the scene.
//
//   cavity_bench [--backend gl|vk|all] [--sweep gpu|cpu|auto] [--iterations N]
//                [google benchmark flags: --benchmark_filter=..., --benchmark_format=json, ...]
#include "bench_runner.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>

int main(int argc, char** argv) {
    cavity::bench::Options options;
    std::vector<char*> rest{argv[0]};
    for (int i = 1; i < argc; ++i) {
        auto take = [&](const char* flag) -> const char* {
            const size_t n = std::strlen(flag);
            if (std::strncmp(argv[i], flag, n) == 0 && argv[i][n] == '=') return argv[i] + n + 1;
            if (std::strcmp(argv[i], flag) == 0 && i + 1 < argc) return argv[++i];
            return nullptr;
        };
        if (const char* v = take("--backend")) options.backend = v;
        else if (const char* v = take("--sweep")) options.sweep = v;
        else if (const char* v = take("--iterations")) options.iterations = std::atoi(v);
        else if (const char* v = take("--warmup")) options.warmup = std::atoi(v);
        else if (const char* v = take("--device")) options.device = std::atoi(v);
        else rest.push_back(argv[i]);
    }
    int n = int(rest.size());
    benchmark::Initialize(&n, rest.data());
    if (benchmark::ReportUnrecognizedArguments(n, rest.data())) return 2;
    auto registered = cavity::bench::registerSweep(options);
    if (!registered) {
        std::cerr << "cavity_bench: " << registered.error().message << "\n";
        return static_cast<int>(registered.error().code);
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    cavity::bench::releaseBackends();
    return 0;
}
