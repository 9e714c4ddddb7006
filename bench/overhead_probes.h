// Benchmarks of what every pass time stands on, beside the sweep's
// configurations (docs/timing.md, "GL's gap on the H200"):
//   timer/empty_scope/<api>            a timestamp pair with nothing between
//   timer/empty_chain/<WxH>/<api>      a dispatch of WxH invocations that does nothing, at
//                                      the sweep's size, twice it, and a half, a quarter
//                                      and an eighth of it (its counter "workgroups")
//   timer/empty_chain_one_scope/<WxH>/<api>  the empty chain with one scope around the passes
//                                      after the first: a pass's cost without its own timestamps
//   timer/store_chain/<WxH>/<api>      a dispatch that stores one RGBA8 texel an invocation
// The chains are 8 such passes a barrier() apart, each into its own image,
// so that with CAVITY_NO_BARRIERS=1 or CAVITY_FULL_BARRIERS=1 they measure
// what the barriers cost and nothing else changes.
#pragma once

#include "backend.h"

namespace cavity::bench {

// Registers the probes of one started backend; returns how many.
int registerOverheadProbes(gpu::Backend& gpu, gpu::Api api, int width, int height);

}  // namespace cavity::bench
