// The benchmark sweep, declared once: for each AO pipeline, one axis at a
// time around its default configuration, plus the full product of sample
// count x blur radius x full/half at 1920x1080 (compute stage) for the
// screen-space pipelines. The SDF AO family gets the one-axis sweeps on the
// compute stage and its default configuration on the fragment stage: its
// blur and upsample passes are the same passes the screen-space sweep already
// measures, and with all of it the GPU sweep no longer fits one 10-minute
// call (on the H200 622 benchmarks came too close to it, the SDF fragment
// axes a large part of them; the full product would be 1102; study
// 2026-11-30_h200_full_sweep). Since then the SDF
// family also gets samples x half at the default blur (compute), for the
// quality-cost chart, and hemisphere_cosine the screen-space product, so the
// whole GPU sweep no longer fits one call: split it with
// --benchmark_filter (scripts/gpu_quality_cost.sh runs the part the chart
// needs, well within one call). Both the benchmark runner and its tests
// read this list; nothing is registered by hand.
#pragma once

#include "plan/namespace.h"
#include "core/config.h"

#include <vector>

namespace cavity::plan {

struct SweepAxes {
    std::vector<int> samples{4, 8, 16, 32, 64};
    std::vector<int> blurs{0, 1, 2, 4, 8};
    std::vector<std::pair<int, int>> sizes{{320, 180}, {1920, 1080}, {3840, 2160}};
    std::pair<int, int> defaultSize{1920, 1080};
    bool product = true;          // the samples x blur x full/half product at defaultSize (screen-space pipelines)
    bool fragmentAxes = true;     // one-axis sweeps on the fragment stage too (else its default only)
};

// On a GPU: everything above. On a CPU renderer (llvmpipe, lavapipe): 320x180,
// samples {4, 16, 64}, blur {0, 4}, no product, fragment default only, so the
// sweep stays under three minutes on two cores.
SweepAxes gpuSweep();
SweepAxes cpuSweep();

// Every configuration, for the given APIs, deduplicated by configId, in a
// stable order.
std::vector<RunConfig> benchmarkSweep(const SweepAxes& axes, const std::vector<gpu::Api>& apis);

// The AO pipelines (kernels of role "ao"), in declaration order.
std::vector<std::string> aoKernels();

}  // namespace cavity::plan