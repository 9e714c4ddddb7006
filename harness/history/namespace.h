// What history/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::history without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/digest.h"
#include "core/json_file.h"
#include "stats/stats.h"

namespace cavity::history {
using core::digestText;
using core::fnv1a64;
using core::nullNonFiniteTokens;
using core::readJsonFile;
using core::writeFileAtomically;
using stats::percentile;
}  // namespace cavity::history
