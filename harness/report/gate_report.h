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

// gate.json, junit.xml, summary.md, status.json and index.html under outDir.
// reportUrl: where index.html will be published (a CI artifact's URL), for
// summary.md's link and status.json; empty: index.html beside summary.md.
Status writeReports(const GateRun& run, const std::string& outDir, const std::string& reportUrl = "");

// status.json: a commit status as a CI step posts it (GitHub's statuses API:
// state success / failure / error, a description of at most 140
// characters, target_url, context "cavity/gate/<matrix>"); its schema is
// harness/report/status.schema.json.
constexpr size_t kStatusDescriptionMax = 140;
nlohmann::json commitStatus(const GateRun& run, const std::string& reportUrl);

std::string junitXml(const GateRun& run);
// At most kSummaryLines lines for any number of failures; its last line
// links `reportUrl` (index.html beside it by default).
constexpr size_t kSummaryLines = 30;
std::string summaryMarkdown(const GateRun& run, const std::string& reportUrl = "index.html");
// What index.html is built from: {"gate": toJson(run), "view": {...}}, the
// view holding what only the page shows (order, labels, verdict notes,
// images as data: URIs by path, the heat-map scale, charts).
// chartsDir: a folder of charts (index.json from scripts/charts/charts.py) to embed, if it exists.
nlohmann::json reportData(const GateRun& run, const std::string& chartsDir);
// harness/report/index.html with report.js and reportData inlined.
Result<std::string> reportHtml(const GateRun& run, const std::string& chartsDir);

}  // namespace cavity::report
