// `cavity run`'s index.html: a contact sheet of every configuration's images
// and a chart per kernel of its AO pipeline times, one page that opens from
// the run's folder with no network (Chart.js inlined).
#pragma once

#include "report/namespace.h"

#include <string>
#include <vector>

namespace cavity::report {

// The page's data, one object per configuration (tests read it back).
nlohmann::json runPageData(const std::vector<measure::RunRecord>& runs, const std::string& command);

// Writes DIR/index.html atomically; its images are the PNGs the run wrote
// under DIR, linked by their relative paths.
Status writeRunPage(const std::string& dir, const std::vector<measure::RunRecord>& runs, const std::string& command);

}  // namespace cavity::report
