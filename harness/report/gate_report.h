// The gate's verdicts for people and CI systems: junit.xml (one test case
// per configuration and check), summary.md (short enough for a pull-request
// comment) and index.html (self-contained: images embedded, no server, no
// network; failing configurations first). index.html is the page in
// harness/report/ (embedded at build time) with the report's data inlined:
// its script builds the page from that data in the browser.
#pragma once

#include "report/namespace.h"
#include "gate/gate.h"

#include <string>

namespace cavity::report {

Status writeReports(const GateRun& run, const std::string& outDir);

std::string junitXml(const GateRun& run);
std::string summaryMarkdown(const GateRun& run);
// What index.html is built from: {"gate": toJson(run), "view": {...}}, the
// view holding what only the page shows (order, labels, verdict notes,
// images as data: URIs by path, the heat-map scale, charts).
// chartsDir: a folder of charts (index.json from scripts/charts.py) to embed, if it exists.
nlohmann::json reportData(const GateRun& run, const std::string& chartsDir);
// harness/report/index.html with report.js and reportData inlined.
Result<std::string> reportHtml(const GateRun& run, const std::string& chartsDir);

}  // namespace cavity::report
