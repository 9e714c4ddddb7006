// cavity_bench's console: one line per configuration (its pipeline time,
// each pass's time, frames, clock and noise), and per repetition set its
// median and spread, in place of Google Benchmark's table, whose user
// counters run to 400 characters a line and print the spread of a constant
// counter as "-nan%". The JSON file (per_pass_reporter.h) keeps everything.
#pragma once

#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace cavity::bench {

class ConsoleReporter : public benchmark::BenchmarkReporter {
public:
    bool ReportContext(const Context& context) override;
    void ReportRuns(const std::vector<Run>& runs) override;

private:
    std::map<std::string, std::vector<double>> pipelineMs_;   // each configuration's repetitions so far
};

}  // namespace cavity::bench
