// `cavity history chart`: one self-contained HTML page (Chart.js inlined
// at build time from Debian's libjs-chart.js; nothing fetched when it is
// viewed) with a chart per series, and a PNG of it through headless
// Chromium where Chromium is installed.
#pragma once

#include "history/alerts.h"

namespace cavity::history {

struct ChartOptions {
    std::string db;               // where the data came from (for the page's header)
    DetectorOptions detector;
};

// The y axis' title for a clock: "GPU timestamps, ms", "wall clock, CPU
// renderer, ms" (a software renderer) or "wall clock, ms".
std::string axisLabel(const Series& s);

// The page's text.
std::string chartPage(const std::vector<Series>& series, const ChartOptions& options);

// Writes DIR/index.html (DIR created when missing). Bad input when DIR is a
// file or cannot be created.
Result<std::string> writeChartPage(const std::string& dir, const std::vector<Series>& series, const ChartOptions& options);

// DIR/index.png of the page, `width` pixels wide and as tall as its charts
// (up to a limit), through `chromium --headless --screenshot`. The path
// written, or "" with `why` saying what stopped it (no chromium on PATH, or
// chromium failed).
std::string screenshot(const std::string& html, const std::string& png, size_t charts, std::string& why);

}  // namespace cavity::history
