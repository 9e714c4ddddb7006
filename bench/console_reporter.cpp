#include "console_reporter.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>

namespace cavity::bench {

namespace {

// "corner/.../vk/compute/iterations:1/manual_time" -> "corner/.../vk/compute"
std::string configurationOf(const std::string& name) {
    const size_t at = name.find("/iterations:");
    return at == std::string::npos ? name : name.substr(0, at);
}

std::string number(double v, const char* format = "%.4f") {
    if (!std::isfinite(v)) return "-";
    char b[32];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

double counter(const benchmark::BenchmarkReporter::Run& run, const std::string& name) {
    const auto c = run.counters.find(name);
    return c == run.counters.end() ? NAN : double(c->second.value);
}

// pass_<name>_ms counters, in the pipeline's order where the name says it
// (the counters come sorted by name).
std::string passes(const benchmark::BenchmarkReporter::Run& run, const char* format) {
    std::string out;
    for (const auto& [name, c] : run.counters)
        if (name.rfind("pass_", 0) == 0 && name.size() > 8 && name.compare(name.size() - 3, 3, "_ms") == 0)
            out += "  " + name.substr(5, name.size() - 8) + " " + number(c.value, format);
    return out;
}

double milliseconds(const benchmark::BenchmarkReporter::Run& run) {
    return run.GetAdjustedRealTime() * 1e3 / benchmark::GetTimeUnitMultiplier(run.time_unit);
}

}  // namespace

bool ConsoleReporter::ReportContext(const Context& context) {
    // Google Benchmark's own header, less its warning that the library was
    // built as DEBUG, which it prints for Debian's libbenchmark: that build
    // is the library's, whose loop only calls Cavity's measurement (GPU
    // timestamps, or Cavity's own wall clock), built -O3. Said once instead.
    std::ostringstream basic;
    PrintBasicContext(&basic, context);
    std::istringstream lines(basic.str());
    bool debugLibrary = false;
    for (std::string line; std::getline(lines, line);) {
        if (line.find("Library was built as DEBUG") != std::string::npos) debugLibrary = true;
        else GetOutputStream() << line << "\n";
    }
    if (debugLibrary)
        GetOutputStream() << "note: Google Benchmark (libbenchmark) was built as DEBUG; it only runs the loop around "
                             "Cavity's measurement, which is GPU timestamps or Cavity's wall clock in -O3 code, so the "
                             "times below are not affected\n";
    GetOutputStream() << "\nconfiguration  pipeline ms  passes (ms)  [frames, clock, noise]\n";
    return true;
}

void ConsoleReporter::ReportRuns(const std::vector<Run>& runs) {
    std::ostream& out = GetOutputStream();
    for (const auto& run : runs) {
        const std::string id = configurationOf(run.benchmark_name());
        if (run.error_occurred) {
            out << id << "  error: " << run.error_message << "\n";
            continue;
        }
        if (run.run_type == Run::RT_Aggregate) {
            // The median of the repetitions, and their spread as the
            // coefficient of variation of the pipeline times seen here (the
            // other aggregates are in the JSON).
            if (run.aggregate_name == "median") {
                const auto& v = pipelineMs_[id];
                double mean = 0, var = 0;
                for (double x : v) mean += x / double(v.size());
                for (double x : v) var += (x - mean) * (x - mean) / double(v.size() > 1 ? v.size() - 1 : 1);
                out << "  median of " << v.size() << ": " << number(milliseconds(run)) << passes(run, "%.4f")
                    << "  [cv " << (v.size() > 1 && mean > 0 ? number(100 * std::sqrt(var) / mean, "%.2f%%") : "-") << "]\n";
            }
            continue;
        }
        if (id.rfind("timer/", 0) == 0) {
            out << id << "  " << number(milliseconds(run) * 1e3, "%.3f")
                << (id.find("_chain") != std::string::npos ? " us a pass\n" : " us a scope\n");
            continue;
        }
        pipelineMs_[id].push_back(milliseconds(run));
        const double noise = counter(run, "noise_pct");
        out << id << "  " << number(milliseconds(run)) << passes(run, "%.4f") << "  [" << number(counter(run, "frames"), "%.0f")
            << " frames, " << run.report_label << ", noise " << (noise >= 0 ? number(noise, "%.2f%%") : "-") << "]\n";
    }
}

}  // namespace cavity::bench
