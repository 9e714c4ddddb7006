// What `cavity quality` recommends: each (kernel, samples) with its mean
// error over the scenes measured and, given a benchmark file (--cost), its
// AO pipeline's time; the Pareto front of the screen-space kernels (those an
// engine can run on its own G-buffer: not the SDF family, which needs the
// scene's distance function) and the most accurate of them within a budget.
#pragma once

#include "imports.h"
#include "measure/quality.h"
#include "result.h"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cavity::flags {


struct Candidate {
    std::string kernel;
    int samples = 0;
    double mae = 0;                 // mean over the scenes
    std::optional<double> costMs;   // the AO pipeline's median, from --cost
    bool screenSpace = true;
};

// (kernel, samples) -> the AO pipeline's time in ms: from cavity_bench JSON
// (its `pipeline`) or a results.json (every pass but the G-buffer), the
// median over the configurations of that kernel and sample count at `half`
// and the largest size the file has for it.
Result<std::map<std::pair<std::string, int>, double>> loadCosts(const std::string& path, bool half);

// Where loadCosts's times come from, in one line for the table: the file,
// the APIs, stages, sizes and clocks of the configurations it read, and
// "a software renderer" when the file says so (its times are the host
// CPU's: no GPU budget follows from them).
struct CostSource {
    std::string text;
    bool softwareRenderer = false;
};
Result<CostSource> costSource(const std::string& path, bool half);

std::vector<Candidate> candidates(const std::vector<QualityRow>& rows,
                                  const std::map<std::pair<std::string, int>, double>& costs);
// The screen-space candidates no other beats on both error and time, cheapest first.
std::vector<Candidate> paretoFront(const std::vector<Candidate>& all);
// The screen-space candidate with the least error whose time is within the budget.
std::optional<Candidate> bestWithin(const std::vector<Candidate>& all, double budgetMs);

nlohmann::json candidateJson(const Candidate& c);

}  // namespace cavity::flags
