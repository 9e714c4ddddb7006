// What plan/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::plan without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/config.h"
#include "core/digest.h"
#include "core/json_file.h"
#include "core/json_input.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"

namespace cavity::plan {
using core::digestText;
using core::fnv1a64;
using core::JsonObject;
using core::onlyKeys;
using core::parseResolution;
using core::readJsonFile;
using core::RunConfig;
using core::setParam;
using core::writeFileAtomically;
using pipeline::configId;
using pipeline::supportsHalf;
using pipeline::validate;
}  // namespace cavity::plan
