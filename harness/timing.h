// Measuring a pipeline: warm-up frames, then N frames each timed two ways,
// by the backend's timestamp scopes and by the wall clock with the queue
// drained before and after. The GPU clock is used only when it brackets the
// work; otherwise (llvmpipe's GL timers, see ../shared/docs/GPU.md) every pass
// is re-timed alone by the drained wall clock, and the result says so.
#pragma once

#include "backend.h"
#include "pipeline.h"
#include "stats.h"

#include <string>
#include <vector>

namespace cavity {

struct Series {
    std::string name;
    std::vector<double> ms;      // one sample per measured frame
    Stats stats;
};

struct Timing {
    std::string clock;           // "gpu-timestamp" or "wall"
    std::string clockNote;       // why the wall clock was used, when it was
    std::vector<Series> passes;  // in pass order, on `clock`
    Series frame;                // the whole frame, on `clock`
    Series frameWall;            // drained wall time of each frame (always)
    Series frameGpu;             // sum of the pass timestamps of each frame (always)
};

// When the GPU timestamps are believed: they may not exceed the drained wall
// time (plus timer slop), and they must account for at least half of it
// unless the difference is within the fixed submission overhead.
struct ClockCheck {
    double maxOverWall = 1.05, slopMs = 0.02;
    double minFraction = 0.5, overheadMs = 0.3;
    bool trusted(double gpuMs, double wallMs) const;
};

Result<Timing> measure(gpu::Backend& gpu, PassChain& chain, int warmup, int frames,
                       const ClockCheck& check = {});

}  // namespace cavity
