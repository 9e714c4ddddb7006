// What every gate report says the same way: the order failures come in,
// the note of a verdict that is not a plain pass or fail, the counts line,
// numbers. Shared by junit.xml, summary.md and index.html.
#pragma once

#include "report/namespace.h"
#include "gate/gate.h"

#include <string>
#include <vector>

namespace cavity::report {

// A number in `digits` significant digits; "inf" for infinity and the
// sentinel of "no finite value".
std::string num(double x, int digits = 4);
// How far a result is past its limits: the largest ratio of a metric to its
// tolerance (or of a pass's median to its budget) over its images; 1e300
// for an error, a non-finite pixel or a known-bad digest.
double severity(const ConfigResult& r);
// The results, failures first (what fails the gate, then what is reported
// but not fatal: flaky, expected failures, known flakes, changes), the worst
// first within each (severity), then by id.
std::vector<const ConfigResult*> ordered(const GateRun& run);
// Lines joined with "; ".
std::string joined(const std::vector<std::string>& lines);
// One line for a verdict that is not a plain pass (a failure: the command
// that accepts its configuration alone); empty otherwise.
// `idPattern`: the regex the printed commands select with, when a card
// stands for more than this configuration (empty: its own id, escaped as is).
// `accept`: acceptArgs(run), the flags the accept commands need.
std::string verdictNote(const ConfigResult& r, const std::string& idPattern = "", const std::string& accept = "");
// The flags `baselines update` and `approve` need to accept this run's
// images: --from its folder, --with-kernel-source when sources were
// replaced, and --kernels for each package it loaded.
std::string acceptArgs(const GateRun& run);
// "3 passed, 1 flaky, ...": every verdict that occurred, in a fixed order.
std::string countsText(const GateRun& run);

}  // namespace cavity::report
