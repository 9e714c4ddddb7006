// Registration and the body of every Cavity benchmark.
#pragma once

#include "result.h"

#include <string>

namespace cavity::bench {

struct Options {
    std::string backend = "all";   // gl, vk, all
    std::string sweep = "auto";    // gpu, cpu, auto (cpu when every started backend is a software renderer)
    int iterations = 0;            // 0: 50 on a GPU, 5 on a CPU renderer
    int warmup = 0;                // 0: 5 on a GPU, 1 on a CPU renderer
    int device = 0;
};

// Starts the backends, adds device context to the JSON, registers one
// benchmark per sweep configuration. Returns how many were registered; fails
// (BackendUnavailable) only when no backend starts.
Result<int> registerSweep(const Options& o);
void releaseBackends();

}  // namespace cavity::bench
