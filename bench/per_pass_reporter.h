// Google Benchmark's JSON, plus one entry per pass. Its compare.py judges a
// benchmark by its time alone (here the AO pipeline), so a pass that got
// slower while another got faster is invisible to it. For every run (each
// repetition and each aggregate) of `<id>` carrying counters pass_<p>_ms,
// this reporter also writes a run named `<id>@<p>` whose time is that
// counter, so `compare.py benchmarks old.json new.json` lists every pass.
// `cavity compare` skips the `@` entries: it reads the counters themselves.
// A pass with a floor (counters floor_<p>_ms, over_floor_<p>) keeps them on
// its entry as floor_ms and measured_over_floor.
#pragma once

#include <benchmark/benchmark.h>

namespace cavity::bench {

class PerPassJsonReporter : public benchmark::JSONReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override;
};

}  // namespace cavity::bench
