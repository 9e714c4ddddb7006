// Google Benchmark JSON as cavity_bench writes it (bench/bench_runner.cpp):
// one "iteration" entry per repetition, named by the configuration id, whose
// real_time is the AO pipeline and whose counters pass_<name>_ms carry each
// pass's median over that repetition's iterations.
#include "compare/namespace.h"
#include "compare/sample_sets.h"

#include <array>
#include <cmath>
#include <cctype>

namespace cavity::compare {

using nlohmann::json;

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A name part Google Benchmark appends after the benchmark's own name.
bool benchmarkPart(const std::string& part) {
    static const std::array<const char*, 3> words = {"manual_time", "real_time", "process_time"};
    static const std::array<const char*, 5> keys = {"iterations:", "repeats:", "threads:", "min_time:",
                                                    "min_warmup_time:"};
    for (const char* w : words)
        if (part == w) return true;
    for (const char* k : keys)
        if (part.rfind(k, 0) == 0) return true;
    return false;
}

// Milliseconds per unit of Google Benchmark's time_unit.
bool msPerUnit(const std::string& unit, double& factor) {
    if (unit == "ns") factor = 1e-6;
    else if (unit == "us") factor = 1e-3;
    else if (unit == "ms") factor = 1.0;
    else if (unit == "s") factor = 1e3;
    else return false;
    return true;
}

std::string stringOr(const json& b, const char* key, const std::string& fallback) {
    return b.contains(key) && b[key].is_string() ? b[key].get<std::string>() : fallback;
}

}  // namespace

std::string configurationIdOf(const std::string& runName) {
    std::string s = runName;
    for (size_t slash = s.rfind('/'); slash != std::string::npos && benchmarkPart(s.substr(slash + 1));
         slash = s.rfind('/'))
        s.erase(slash);
    return s;
}

std::string clockOfLabel(const std::string& label) {
    for (size_t at = label.find("clock="); at != std::string::npos; at = label.find("clock=", at + 1)) {
        if (at > 0 && !std::isspace(static_cast<unsigned char>(label[at - 1]))) continue;   // "wallclock=" is not ours
        size_t end = at + 6;
        while (end < label.size() && !std::isspace(static_cast<unsigned char>(label[end]))) ++end;
        if (end > at + 6) return label.substr(at + 6, end - at - 6);
    }
    return "unknown";
}

Result<SampleSets> readBenchmarkJson(const json& doc, const std::string& path) {
    SampleSets out;
    out.path = path;
    out.format = "google-benchmark";
    if (doc.contains("context") && doc["context"].is_object())
        out.softwareRenderer = doc["context"].value("cavity_software_renderer", "") == "true";
    const json& benchmarks = doc["benchmarks"];
    for (size_t i = 0; i < benchmarks.size(); ++i) {
        const json& b = benchmarks[i];
        const std::string where = path + ": benchmarks[" + std::to_string(i) + "]";
        if (!b.is_object()) return badInput(where + ": must be an object");
        const std::string name = stringOr(b, "run_name", stringOr(b, "name", ""));
        if (name.empty()) return badInput(where + ": has no name");
        if (b.value("error_occurred", false)) {
            ++out.skippedErrors;
            continue;
        }
        // Older Google Benchmark wrote no run_type; its aggregates still carry aggregate_name.
        const std::string runType = stringOr(b, "run_type", b.contains("aggregate_name") ? "aggregate" : "iteration");
        if (runType != "iteration") continue;
        if (name.find('@') != std::string::npos) {
            ++out.skippedMirrors;
            continue;
        }
        const std::string unit = stringOr(b, "time_unit", "ns");
        double factor = 0;
        if (!msPerUnit(unit, factor))
            return badInput(where + " " + name + ": time_unit " + unit + ": must be ns, us, ms or s");
        // A NaN (written as a bare NaN, read as null) is no time either: an
        // iteration without error_occurred must have measured one.
        if (!b.contains("real_time") || !b["real_time"].is_number())
            return badInput(where + " " + name + ": real_time: must be a number (" +
                            (b.contains("real_time") ? "NaN or " + std::string(b["real_time"].type_name()) : std::string("missing")) +
                            " in an iteration without error_occurred)");

        const std::string id = configurationIdOf(name);
        const std::string clock = clockOfLabel(stringOr(b, "label", ""));
        // The repetition's median SM clock (cavity_bench writes it where NVML reads one).
        const double smMhz =
            b.contains("sm_mhz_median") && b["sm_mhz_median"].is_number() ? b["sm_mhz_median"].get<double>() : NAN;
        // A negative or infinite time was never measured: the file is wrong.
        const auto time = [&](const std::string& key, double ms) -> Status {
            if (std::isfinite(ms) && ms >= 0) return {};
            return badInput(where + " " + name + ": " + key + " " + std::to_string(ms) + " ms: a time must be finite and >= 0");
        };
        CAVITY_TRY(time("real_time", b["real_time"].get<double>() * factor));
        out.at(id, kPipelinePass).add(b["real_time"].get<double>() * factor, clock, smMhz);
        for (const auto& [key, value] : b.items()) {
            if (key.size() <= 8 || key.rfind("pass_", 0) != 0 || !endsWith(key, "_ms")) continue;
            SampleSet& pass = out.at(id, key.substr(5, key.size() - 8));
            if (!value.is_number()) continue;
            CAVITY_TRY(time(key, value.get<double>()));
            pass.add(value.get<double>(), clock, smMhz);
        }
    }
    return out;
}

}  // namespace cavity::compare