// What stats/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::stats without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

namespace cavity::stats {
}  // namespace cavity::stats
