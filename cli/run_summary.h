// What `cavity run` says when it is done: a summary of at most 15 lines on
// stdout, and the long table (every pass of every configuration, its clock,
// the notes) that goes to table.txt, or to stdout as well with --table.
#pragma once

#include "measure/results.h"

#include <string>
#include <vector>

namespace cavity::cli {

// Per kernel: its clock, the fastest and the slowest configuration, half
// against full and GL against Vulkan as geometric means over matched pairs,
// each only where both sides ran on one clock (else it says why not).
// `files`: the lines that close it (the paths written).
std::string runSummary(const std::vector<measure::RunRecord>& runs, const std::vector<std::string>& files);

// Every pass of every configuration with its clock, and the notes.
std::string runTable(const std::vector<measure::RunRecord>& runs);

}  // namespace cavity::cli
