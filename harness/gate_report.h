// The gate's verdicts for people and CI systems: junit.xml (one test case
// per configuration and check), summary.md (short enough for a pull-request
// comment) and index.html (self-contained: images embedded, no server, no
// network; failing configurations first).
#pragma once

#include "gate.h"

#include <string>

namespace cavity::gate {

Status writeReports(const GateRun& run, const std::string& outDir);

std::string junitXml(const GateRun& run);
std::string summaryMarkdown(const GateRun& run);
// chartsDir: a folder of charts (index.json from scripts/charts.py) to embed, if it exists.
std::string reportHtml(const GateRun& run, const std::string& chartsDir);

}  // namespace cavity::gate
