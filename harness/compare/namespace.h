// What compare/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::compare without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/json_file.h"
#include "core/json_input.h"
#include "measure/results.h"
#include "stats/stats.h"

namespace cavity::compare {
using core::JsonObject;
using core::readJsonFile;
using stats::summarize;
using measure::kResultsSchema;
}  // namespace cavity::compare
