// What cli/ uses from the harness, named one by one: a name here is
// visible inside cavity::cli without qualification. Every other harness
// name is written qualified (core::, measure::).
#pragma once

#include "compare/compare_verdict.h"
#include "compare/sample_sets.h"
#include "core/config.h"
#include "core/image.h"
#include "core/json_file.h"
#include "core/progress.h"
#include "core/text_table.h"
#include "images/gbuffer_import.h"
#include "images/image_io.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "measure/timing.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "report/compare_report.h"
#include "stats/stats.h"

namespace cavity::cli {
using core::GBufferImages;
using core::HostImage;
using core::isKernelParam;
using core::parseResolution;
using core::Progress;
using core::readJsonFile;
using core::RunConfig;
using core::TextTable;
using core::writeFileAtomically;
using stats::Stats;
using pipeline::configId;
using pipeline::supportsHalf;
using pipeline::validate;
using images::importGBuffer;
using images::readImage;
using measure::checkWritableDir;
using measure::checkOutputFiles;
using measure::checkWritableFile;
using measure::resultsDocument;
using measure::runConfig;
using measure::RunError;
using measure::RunOptions;
using measure::RunRecord;
using measure::TimingMode;
using measure::timingModeName;
using measure::utcTimestamp;
using measure::writeJson;
using compare::CompareThresholds;
using compare::loadSampleSets;
using compare::SampleSets;
using report::compareAll;
using report::compareJson;
using report::compareTable;
}  // namespace cavity::cli
