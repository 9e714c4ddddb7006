// What `cavity compare` prints and writes: the rows of two runs side by side,
// as a table for a person and as cavity.compare/1 JSON for a pull-request bot.
#pragma once

#include "report/namespace.h"
#include "compare/compare_verdict.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace cavity::report {

constexpr const char* kCompareSchema = "cavity.compare/1";

// One row per (configuration, pass) found in either run, grouped by
// configuration in the order the old file names them, then the new file's.
std::vector<CompareRow> compareAll(const SampleSets& before, const SampleSets& after, const CompareThresholds& t);

// The table, columns as wide as their widest entry (ids run to 50 characters),
// followed by a count of each verdict and the rule that gave them.
std::string compareTable(const std::vector<CompareRow>& rows, const SampleSets& before, const SampleSets& after,
                         const CompareThresholds& t);

// cavity.compare/1; a number that was not computed is null.
nlohmann::json compareJson(const std::vector<CompareRow>& rows, const SampleSets& before, const SampleSets& after,
                           const CompareThresholds& t);

}  // namespace cavity::report