// The quality table as `quality` prints it: each scene's rows most accurate
// first, each MAE with its interval, `~` where a row cannot be told from the
// one above, and an edited kernel's change against the committed one.
#pragma once

#include "imports.h"
#include "measure/quality.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cavity::flags {

// The two rows of one scene differ by an amount whose 95% interval (a paired
// bootstrap, measure::maeDifference) holds 0.
bool cannotTellApart(const QualityRow& better, const QualityRow& worse);

// The table on stdout; costs: (kernel, samples) -> AO pipeline ms, or empty.
void printQuality(const QualityOptions& o, std::vector<QualityRow> rows,
                  const std::map<std::pair<std::string, int>, double>& costs);

}  // namespace cavity::flags
