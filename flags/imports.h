// What flags/ uses from the harness, named one by one: a name here is
// visible inside cavity::flags without qualification. Every other harness
// name is written qualified (core::, measure::).
#pragma once

#include "core/config.h"
#include "core/digest.h"
#include "core/progress.h"
#include "core/text_table.h"
#include "measure/quality.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "stats/stats.h"

namespace cavity::flags {
using core::digestText;
using core::fnv1a64;
using core::parseResolution;
using core::Progress;
using core::RunConfig;
using core::setParam;
using core::TextTable;
using stats::summarize;
using pipeline::configId;
using pipeline::ReplacedSource;
using pipeline::SourceOverrides;
using pipeline::supportsHalf;
using measure::applySwitches;
using measure::checkWritableDir;
using measure::measureQuality;
using measure::QualityOptions;
using measure::QualityRow;
using measure::writeJson;
}  // namespace cavity::flags
