// What gate/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::gate without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/config.h"
#include "core/digest.h"
#include "core/image.h"
#include "core/json_file.h"
#include "core/json_input.h"
#include "core/progress.h"
#include "images/image_io.h"
#include "images/metrics.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "plan/approvals.h"
#include "plan/matrix.h"
#include "render/render_manifest.h"
#include "render/rendering.h"

namespace cavity::gate {
using core::HostImage;
using core::imageDigest;
using core::JsonObject;
using core::onlyKeys;
using core::Progress;
using core::readJsonFile;
using core::RunConfig;
using pipeline::checkSourcesUsed;
using pipeline::configId;
using pipeline::ReplacedSource;
using pipeline::SourceOverrides;
using images::Encoding;
namespace metrics = images::metrics;
using images::readImage;
using images::writeImage;
using plan::Approval;
using plan::Approvals;
using plan::baselineKey;
using plan::CheckedImage;
using plan::checkedImages;
using plan::checkedShape;
using plan::deviceClass;
using plan::ImageShape;
using plan::inShard;
using plan::loadApprovals;
using plan::loadMatrix;
using plan::Matrix;
using plan::selectEntries;
using plan::shapeText;
using measure::checkWritableDir;
using measure::gitCommit;
using measure::toJson;
using render::RemoteCheck;
using render::toJson;
}  // namespace cavity::gate
