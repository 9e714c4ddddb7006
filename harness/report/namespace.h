// What report/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::report without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "compare/compare_verdict.h"
#include "compare/sample_sets.h"
#include "core/json_file.h"
#include "gate/gate.h"
#include "images/metrics.h"
#include "measure/results.h"
#include "measure/roofline.h"
#include "render/render_manifest.h"

namespace cavity::report {
using core::writeFileAtomically;
namespace metrics = images::metrics;
using measure::describe;
using measure::toJson;
using measure::utcTimestamp;
using measure::writeJson;
using render::toJson;
using gate::ConfigResult;
using gate::GateRun;
using gate::toJson;
using compare::CompareRow;
using compare::compareSeries;
using compare::CompareThresholds;
using compare::kAutoFloorMs;
using compare::kAutoFloorPct;
using compare::SampleSets;
}  // namespace cavity::report
