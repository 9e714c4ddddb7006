// A run file read for the results database: cavity_bench's Google
// Benchmark JSON, `cavity run`'s results.json (cavity.results/1) or the
// gate's gate.json (cavity.gate/1), plain or gzip-compressed. The times come
// from the readers `cavity compare` and `gate merge` use (compare/, gate/),
// so a file holds the same numbers for every command; this adds what those
// readers leave out: each series' device, the repetition order, the memory
// clock, the timing mode and what made the file.
#pragma once

#include "history/namespace.h"
#include "result.h"

#include <string>
#include <vector>

namespace cavity::history {

struct Sample {
    int repetition = 0;   // a repetition (cavity_bench, the gate) or a frame (results.json)
    double ms = 0;
    double smMhz = 0, memMhz = 0;   // 0: the file does not say
};

// One (configuration, pass, device) of one file.
struct PassSeries {
    std::string configId, pass, device, api, clock, timingMode;
    bool softwareRenderer = false;
    std::vector<Sample> samples;
};

struct RunFile {
    std::string path;
    std::string format;       // "google-benchmark", "cavity-results", "cavity-gate"
    std::string digest;       // of the (uncompressed) content
    std::string date;         // the file's own date (UTC ISO 8601), "" when it has none
    std::string device, driver, api, cavityVersion;
    std::vector<PassSeries> series;
};

// A one-line bad-input error names the file on every failure: missing, a
// folder, empty, not one of the three formats, a field of the wrong type, a
// time that is not a finite number, a file with no time at all.
Result<RunFile> readRunFile(const std::string& path);

// "2026-11-30T12:59:27+00:00", "2026-11-30T12:59:27Z", "2026-11-30 12:59:27",
// "2026-11-30" -> "2026-11-30T12:59:27Z" (UTC; an offset is applied). Empty
// when `text` is none of these or names no real date and time.
std::string normalizeDate(const std::string& text);

}  // namespace cavity::history
