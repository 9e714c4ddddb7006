// Registration and the body of every Cavity benchmark.
#pragma once

#include "imports.h"
#include "pipeline/pipeline.h"
#include "result.h"
#include "measure/timing.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cavity::bench {


struct Options {
    std::string backend = "all";   // gl, vk, all
    std::string sweep = "auto";    // gpu, cpu, auto (cpu when every started backend is a software renderer)
    // Unset: the device's defaults (harness/measure/timing.h); on a CPU renderer 5
    // frames after 1 warm-up frame.
    std::optional<int> frames, warmup;
    std::optional<TimingMode> mode;
    std::optional<double> maxNoise, maxSeconds;
    PlantedSlowdown plant;         // --plant ao:120,blur:40, every configuration (scripts/gpu_verdict.sh)
    std::map<std::string, PlantedSlowdown> plantById;   // --plant-file: {"<id>": {"ao": 120}}; wins over plant
    SourceOverrides overrides;     // --kernel-source NAME=FILE: kernels/NAME replaced, every configuration
    std::vector<ReplacedSource> replaced;   // the same, as the JSON context records them
    std::string filter;            // --benchmark_filter as given (a valid regex): which configurations replaced sources must reach
    int device = 0;
};

// Starts the backends, adds device context to the JSON, registers one
// benchmark per sweep configuration. Returns how many were registered; fails
// (BackendUnavailable) only when no backend starts.
Result<int> registerSweep(const Options& o);
void releaseBackends();

// The benchmarks that failed to measure (a kernel source that does not
// compile, a GPU error): Google Benchmark reports them and carries on, so
// main() turns them into its exit code, and a run that measured nothing, or
// part of what it was asked, never exits 0.
struct Failure {
    std::string id;
    Error error;
};
void noteFailure(const std::string& id, const Error& error);
const std::vector<Failure>& failures();

}  // namespace cavity::bench
