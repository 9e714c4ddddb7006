// What measure/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::measure without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/config.h"
#include "core/image.h"
#include "core/json_file.h"
#include "images/gbuffer_import.h"
#include "images/image_io.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "stats/stats.h"

namespace cavity::measure {
using core::GBufferImages;
using core::HostImage;
using core::importStem;
using core::RunConfig;
using core::setParam;
using core::writeFileAtomically;
using stats::Stats;
using stats::summarize;
using pipeline::configId;
using pipeline::NonFinite;
using pipeline::PassChain;
using pipeline::PassSpec;
using pipeline::renderImages;
using pipeline::SourceOverrides;
using pipeline::supportsHalf;
using pipeline::userOutputs;
using images::Encoding;
using images::importGBuffer;
using images::writeImage;
}  // namespace cavity::measure
