#include "imports.h"
#include "per_pass_reporter.h"

#include <string>

namespace cavity::bench {


namespace {

constexpr const char* kPrefix = "pass_";
constexpr const char* kSuffix = "_ms";

// The pass name of a counter called pass_<name>_ms, or empty.
std::string passOf(const std::string& counter) {
    const std::string p = kPrefix, s = kSuffix;
    if (counter.size() <= p.size() + s.size() || counter.rfind(p, 0) != 0 ||
        counter.compare(counter.size() - s.size(), s.size(), s) != 0)
        return {};
    return counter.substr(p.size(), counter.size() - p.size() - s.size());
}

}  // namespace

void PerPassJsonReporter::ReportRuns(const std::vector<Run>& runs) {
    std::vector<Run> all = runs;
    for (const Run& r : runs) {
        if (r.error_occurred) continue;
        for (const auto& [name, counter] : r.counters) {
            const std::string pass = passOf(name);
            if (pass.empty()) continue;
            Run p = r;
            p.run_name.function_name += "@" + pass;
            p.counters.clear();
            for (const auto& [from, to] : {std::pair{"floor_" + pass + "_ms", "floor_ms"},
                                           std::pair{"over_floor_" + pass, "measured_over_floor"}})
                if (auto it = r.counters.find(from); it != r.counters.end()) p.counters[to] = it->second;
            // Google Benchmark reports accumulated time x unit / iterations
            // for times, and the bare value for a percentage (the cv
            // aggregate), so a time in ms becomes seconds x iterations.
            const bool percentage = r.run_type == Run::RT_Aggregate &&
                                    r.aggregate_unit == benchmark::StatisticUnit::kPercentage;
            const double v = counter.value;
            p.real_accumulated_time = percentage ? v : v / 1000.0 * double(r.iterations);
            p.cpu_accumulated_time = p.real_accumulated_time;
            p.time_unit = benchmark::kMillisecond;
            all.push_back(std::move(p));
        }
    }
    JSONReporter::ReportRuns(all);
}

}  // namespace cavity::bench
