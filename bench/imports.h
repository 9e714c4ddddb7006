// What bench/ uses from the harness, named one by one: a name here is
// visible inside cavity::bench without qualification. Every other harness
// name is written qualified (core::, measure::).
#pragma once

#include "core/config.h"
#include "measure/gpu_clocks.h"
#include "measure/roofline.h"
#include "measure/timing.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "plan/sweep.h"
#include "stats/stats.h"

namespace cavity::bench {
using core::RunConfig;
using stats::summarize;
using pipeline::buildPasses;
using pipeline::checkSourcesUsed;
using pipeline::configId;
using pipeline::PassChain;
using pipeline::PassSpec;
using pipeline::PlantedSlowdown;
using pipeline::ReplacedSource;
using pipeline::SourceOverrides;
using plan::benchmarkSweep;
using plan::cpuSweep;
using plan::gpuSweep;
using measure::defaultTimingOptions;
using measure::describe;
using measure::DeviceFloor;
using measure::deviceFloor;
using measure::GpuClocks;
using measure::measurePasses;
using measure::passFloor;
using measure::Timing;
using measure::TimingMode;
using measure::timingModeName;
using measure::TimingOptions;
}  // namespace cavity::bench
