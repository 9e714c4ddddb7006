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

// A string field, or `fallback` where it is absent; any other type is the
// file's error, said with `where`.
Result<std::string> stringOr(const json& b, const char* key, const std::string& fallback, const std::string& where) {
    if (!b.contains(key)) return fallback;
    if (!b[key].is_string()) return badInput(where + ": " + key + " = " + core::shortDump(b[key]) + ": must be a string");
    return b[key].get<std::string>();
}

// An iteration entry's unit (as ms per unit), time and counts, checked:
// Google Benchmark always writes the unit, and a guess would be off by a
// factor of up to 10^9.
Result<double> iterationFields(const json& b, const std::string& where) {
    if (!b.contains("time_unit")) return badInput(where + ": time_unit: missing (ns, us, ms or s)");
    const json& unit = b["time_unit"];
    double factor = 0;
    if (!unit.is_string() || !msPerUnit(unit.get<std::string>(), factor))
        return badInput(where + ": time_unit " + core::shortDump(unit) + ": must be ns, us, ms or s");
    // A NaN (written as a bare NaN, read as null) is no time either: an
    // iteration without error_occurred must have measured one.
    if (!b.contains("real_time") || !b["real_time"].is_number())
        return badInput(where + ": real_time: must be a number (" +
                        (b.contains("real_time") ? "NaN or " + std::string(b["real_time"].type_name()) : std::string("missing")) +
                        " in an iteration without error_occurred)");
    for (const char* key : {"repetition_index", "iterations"})
        if (b.contains(key)) {
            const json& v = b[key];
            const double x = v.is_number() ? v.get<double>() : NAN, least = key[0] == 'i' ? 1 : 0;
            if (!std::isfinite(x) || x != std::floor(x) || x < least || x > 1e9)
                return badInput(where + ": " + key + " = " + core::shortDump(v) + ": must be a whole number >= " +
                                (least > 0 ? "1" : "0"));
        }
    return factor;
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
    if (doc.contains("context") && doc["context"].is_object()) {
        CAVITY_ASSIGN(const std::string software,
                      stringOr(doc["context"], "cavity_software_renderer", "false", path + ": context"));
        if (software != "true" && software != "false")
            return badInput(path + ": context: cavity_software_renderer = " + core::shortDump(software) + ": must be true or false");
        out.softwareRenderer = software == "true";
    }
    const json& benchmarks = doc["benchmarks"];
    for (size_t i = 0; i < benchmarks.size(); ++i) {
        const json& b = benchmarks[i];
        const std::string where = path + ": benchmarks[" + std::to_string(i) + "]";
        if (!b.is_object()) return badInput(where + ": must be an object");
        CAVITY_ASSIGN(const std::string shortName, stringOr(b, "name", "", where));
        CAVITY_ASSIGN(const std::string name, stringOr(b, "run_name", shortName, where));
        if (name.empty()) return badInput(where + ": has no name");
        if (b.contains("error_occurred") && !b["error_occurred"].is_boolean())
            return badInput(where + " " + name + ": error_occurred = " + core::shortDump(b["error_occurred"]) +
                            ": must be true or false");
        if (b.value("error_occurred", false)) {
            ++out.skippedErrors;
            continue;
        }
        // Older Google Benchmark wrote no run_type; its aggregates still carry aggregate_name.
        CAVITY_ASSIGN(const std::string runType,
                      stringOr(b, "run_type", b.contains("aggregate_name") ? "aggregate" : "iteration", where));
        if (runType != "iteration" && runType != "aggregate")
            return badInput(where + " " + name + ": run_type " + core::shortDump(runType) + ": must be iteration or aggregate");
        if (runType != "iteration") continue;
        if (name.find('@') != std::string::npos) {
            ++out.skippedMirrors;
            continue;
        }
        CAVITY_ASSIGN(const double factor, iterationFields(b, where + " " + name));
        const std::string id = configurationIdOf(name);
        CAVITY_ASSIGN(const std::string label, stringOr(b, "label", "", where));
        const std::string clock = clockOfLabel(label);
        // The repetition's median SM clock (cavity_bench writes it where NVML reads one).
        const double smMhz =
            b.contains("sm_mhz_median") && b["sm_mhz_median"].is_number() ? b["sm_mhz_median"].get<double>() : NAN;
        // A negative or infinite time was never measured: the file is wrong.
        const auto time = [&](const std::string& key, double ms) -> Status {
            if (std::isfinite(ms) && ms >= 0 && ms <= measure::kMaxRecordedMs) return {};
            return badInput(where + " " + name + ": " + key + " " + core::shortDump(ms) +
                            " ms: a time must be finite, >= 0 and at most 1e7 ms");
        };
        CAVITY_TRY(time("real_time", b["real_time"].get<double>() * factor));
        out.at(id, kPipelinePass).add(b["real_time"].get<double>() * factor, clock, smMhz);
        for (const auto& [key, value] : b.items()) {
            if (key.size() <= 8 || key.rfind("pass_", 0) != 0 || !endsWith(key, "_ms")) continue;
            SampleSet& pass = out.at(id, key.substr(5, key.size() - 8));
            if (!value.is_number())
                return badInput(where + " " + name + ": " + key + " = " + core::shortDump(value) +
                                ": must be a number (a NaN is written as null)");
            CAVITY_TRY(time(key, value.get<double>()));
            pass.add(value.get<double>(), clock, smMhz);
        }
    }
    return out;
}

}  // namespace cavity::compare