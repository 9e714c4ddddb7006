// The benchmark sweep, declared once: for each AO pipeline, one axis at a
// time around its default configuration, plus the full product of sample
// count x blur radius x full/half at 1920x1080 (compute stage). Both the
// benchmark runner and its tests read this list; nothing is registered by hand.
#pragma once

#include "config.h"

#include <vector>

namespace cavity {

struct SweepAxes {
    std::vector<int> samples{4, 8, 16, 32, 64};
    std::vector<int> blurs{0, 1, 2, 4, 8};
    std::vector<std::pair<int, int>> sizes{{320, 180}, {1920, 1080}, {3840, 2160}};
    std::pair<int, int> defaultSize{1920, 1080};
    bool product = true;          // the samples x blur x full/half product at defaultSize
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

}  // namespace cavity
