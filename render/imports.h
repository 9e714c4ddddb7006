// What render/ uses from the harness, named one by one: a name here is
// visible inside cavity::render without qualification. Every other harness
// name is written qualified (core::, measure::).
#pragma once

#include "core/config.h"
#include "core/image.h"
#include "images/gbuffer_import.h"
#include "images/image_io.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "measure/timing.h"
#include "pipeline/pipeline.h"
#include "render/rendering.h"

namespace cavity::render {
using core::GBufferImages;
using core::HostImage;
using core::RunConfig;
using pipeline::checkSourcesUsed;
using pipeline::ReplacedSource;
using images::Encoding;
using images::importGBuffer;
using images::readImage;
using images::writeImage;
using measure::checkWritableDir;
using measure::gitCommit;
using measure::TimingMode;
using measure::utcTimestamp;
using render::renderEntries;
}  // namespace cavity::render
