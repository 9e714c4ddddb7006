// What render/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::render without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/config.h"
#include "core/digest.h"
#include "core/image.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "measure/timing.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"

namespace cavity::render {
using core::HostImage;
using core::imageDigest;
using core::RunConfig;
using pipeline::configId;
using pipeline::ReplacedSource;
using pipeline::SourceOverrides;
using measure::gitCommit;
using measure::runConfig;
using measure::RunOptions;
using measure::TimingMode;
using measure::toJson;
using measure::writeJson;
}  // namespace cavity::render
