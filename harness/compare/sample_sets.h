// What `cavity compare` compares: for each configuration id and pass, the
// times one run measured, from either file the project writes. A results.json
// gives one sample per frame; Google Benchmark JSON from cavity_bench gives
// one per repetition. The two meet on the configuration id (README,
// "Configuration ids") and the pass name.
#pragma once

#include "compare/namespace.h"
#include "result.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cavity::compare {

// The times of one (configuration, pass), in milliseconds, and the clock that
// took them: "gpu-timestamp" or "wall" (README, "Timing").
struct SampleSet {
    std::vector<double> ms;
    // The SM clock each sample was taken at (its run's or repetition's
    // median, from NVML), beside ms; NaN where the file records none.
    std::vector<double> smMhz;
    std::vector<std::string> clocks;   // each sample's clock, beside ms
    std::string clock;
    // Samples of this series came from different clocks: a wall-clock sample
    // and a timestamp sample measure different things, so they are never pooled.
    bool mixedClocks = false;

    void add(double value, const std::string& sampleClock, double sampleSmMhz = NAN);
    // Every sample's SM clock is known.
    bool smClockKnown() const;
    // The samples taken on `c` alone.
    SampleSet onClock(const std::string& c) const;
};

struct SampleSets {
    std::string path;
    std::string format;   // "cavity-results" or "google-benchmark"
    // (configuration id, pass) in the order the file first names them.
    std::vector<std::pair<std::string, std::string>> order;
    std::map<std::pair<std::string, std::string>, SampleSet> series;
    int skippedErrors = 0;    // benchmark entries with error_occurred
    int skippedMirrors = 0;   // "<id>@<pass>" entries: the same numbers as the counters
    // Measured on a software renderer (a results.json run's device, or
    // cavity_bench's context cavity_software_renderer).
    bool softwareRenderer = false;

    SampleSet& at(const std::string& id, const std::string& pass);
};

// The series' names for the whole of a configuration: results.json times the
// frame (G-buffer included) and the AO pipeline (G-buffer left out);
// cavity_bench's own time (real_time) is the AO pipeline.
constexpr const char* kFramePass = "frame";
constexpr const char* kPipelinePass = "pipeline";

// Reads either format, found from the content. A file that is neither, is
// missing or does not parse is a one-line bad-input error naming it.
Result<SampleSets> loadSampleSets(const std::string& path);

// The two readers, given the parsed document.
// `everySample`: a sample that is not a time (null, written for a NaN) is bad
// input rather than left out: history stores every repetition, and a run
// with a hole in it is not the run that was measured.
Result<SampleSets> readResultsJson(const nlohmann::json& doc, const std::string& path, bool everySample = false);
Result<SampleSets> readBenchmarkJson(const nlohmann::json& doc, const std::string& path);

// The configuration id in a Google Benchmark run name: the name without the
// parts Google Benchmark appends ("/iterations:50", "/repeats:3",
// "/threads:1", "/min_time:...", "/manual_time", "/real_time", ...).
std::string configurationIdOf(const std::string& runName);

// The word after "clock=" in a cavity_bench label ("clock=gpu-timestamp
// mode=batch", "clock=wall (timestamps do not bracket the work)"), or
// "unknown" where the label has none.
std::string clockOfLabel(const std::string& label);

}  // namespace cavity::compare