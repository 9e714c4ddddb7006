#include "history/run_readers.h"
#include "compare/sample_sets.h"
#include "gate/gate.h"

#include <cmath>
#include <functional>
#include <map>
#include <tuple>
#include <sstream>

namespace cavity::history {

using nlohmann::json;

namespace {

std::string text(const json& obj, const char* key) {
    return obj.is_object() && obj.contains(key) && obj[key].is_string() ? obj[key].get<std::string>() : "";
}

double number(const json& obj, const char* key) {
    return obj.is_object() && obj.contains(key) && obj[key].is_number() ? obj[key].get<double>() : 0.0;
}

// "gl: NVIDIA H200/PCIe/SSE2; vk: NVIDIA H200" -> {gl: ..., vk: ...}.
std::map<std::string, std::string> perApi(const std::string& s) {
    std::map<std::string, std::string> out;
    std::stringstream in(s);
    for (std::string part; std::getline(in, part, ';');) {
        const auto colon = part.find(':');
        if (colon == std::string::npos) continue;
        auto trim = [](std::string t) {
            t.erase(0, t.find_first_not_of(' '));
            t.erase(t.find_last_not_of(' ') + 1);
            return t;
        };
        out[trim(part.substr(0, colon))] = trim(part.substr(colon + 1));
    }
    return out;
}

// Each (configuration, pass) of the compare reader as a series, with the
// device its API ran on and the clocks beside each sample.
void addSets(const compare::SampleSets& sets, RunFile& out, const std::function<void(PassSeries&)>& annotate) {
    for (const auto& key : sets.order) {
        const auto& set = sets.series.at(key);
        PassSeries s;
        s.configId = key.first;
        s.pass = key.second;
        s.api = apiOfId(s.configId);
        s.clock = set.clock;
        s.softwareRenderer = sets.softwareRenderer;
        for (size_t i = 0; i < set.ms.size(); ++i)
            s.samples.push_back({int(i), set.ms[i], 0.0, 0.0});
        annotate(s);
        if (s.device.empty()) s.device = out.device.empty() ? "unknown" : out.device;
        out.series.push_back(std::move(s));
    }
}

// The run's own date: absent is "" (the ingest takes the time it stores
// it). One that is not a string, or is empty, is bad input, not silently
// today; the string's form is checked with every format's (readRunFile).
Result<std::string> dateOf(const json& obj, const char* key, const std::string& path, const std::string& where) {
    if (!obj.is_object() || !obj.contains(key) || obj[key].is_null()) return std::string();
    if (obj[key].is_string() && !obj[key].get<std::string>().empty()) return obj[key].get<std::string>();
    return badInput(path + ": " + where + " " + obj[key].dump().substr(0, 40) +
                    ": must be an ISO 8601 date string (2026-11-30T12:00:00Z) or absent");
}

bool looksSoftware(const std::string& device) {
    for (const char* word : {"llvmpipe", "lavapipe", "softpipe", "SwiftShader"})
        if (device.find(word) != std::string::npos) return true;
    return false;
}

}  // namespace

std::string apiOfId(const std::string& id) {
    std::stringstream in(id);
    std::string found;
    for (std::string part; std::getline(in, part, '/');)
        if (part == "gl" || part == "vk") found = part;
    return found;
}

Status readBenchmark(const json& doc, RunFile& out) {
    CAVITY_ASSIGN(const auto sets, compare::readBenchmarkJson(doc, out.path));
    out.format = "google-benchmark";
    const json& ctx = doc.contains("context") ? doc["context"] : json();
    CAVITY_ASSIGN(out.date, dateOf(ctx, "date", out.path, "context.date"));
    out.device = text(ctx, "cavity_device");
    out.driver = text(ctx, "cavity_driver");
    out.api = text(ctx, "cavity_api_versions");
    const auto devices = perApi(out.device);
    const std::string mode = text(ctx, "cavity_timing_mode");
    // The clocks of each repetition, in the order the compare reader took them.
    std::map<std::string, std::vector<std::pair<double, double>>> clocks;
    for (const auto& b : doc["benchmarks"]) {
        const std::string name = text(b, "run_name").empty() ? text(b, "name") : text(b, "run_name");
        // readBenchmarkJson checked every entry's types.
        if (!b.is_object() || b.value("error_occurred", false) || name.find('@') != std::string::npos) continue;
        if (text(b, "run_type") != "" && text(b, "run_type") != "iteration") continue;
        if (!b.contains("run_type") && b.contains("aggregate_name")) continue;
        // A clock that is there is a clock: a string or a negative one is a
        // damaged file, not a run whose clock was not read.
        for (const char* key : {"sm_mhz_median", "mem_mhz_median"})
            if (b.contains(key) && !b[key].is_null() &&
                !(b[key].is_number() && std::isfinite(b[key].get<double>()) && b[key].get<double>() >= 0))
                return badInput(out.path + ": " + name + ": " + key + " " + b[key].dump().substr(0, 40) +
                                ": must be a clock in MHz (a number >= 0) or absent");
        clocks[compare::configurationIdOf(name)].push_back({number(b, "sm_mhz_median"), number(b, "mem_mhz_median")});
    }
    addSets(sets, out, [&](PassSeries& s) {
        const auto d = devices.find(s.api);
        s.device = d != devices.end() ? d->second : out.device;
        s.timingMode = mode;
        const auto& c = clocks[s.configId];
        if (c.size() == s.samples.size())
            for (size_t i = 0; i < c.size(); ++i) std::tie(s.samples[i].smMhz, s.samples[i].memMhz) = c[i];
    });
    return {};
}

Status readResults(const json& doc, RunFile& out) {
    CAVITY_ASSIGN(const auto sets, compare::readResultsJson(doc, out.path, true));
    out.format = "cavity-results";
    CAVITY_ASSIGN(out.date, dateOf(doc, "created_utc", out.path, "created_utc"));
    out.cavityVersion = text(doc, "git_commit");
    struct Run {
        std::string device, driver, apiVersion, mode;
        bool software = false;
        double smMhz = 0, memMhz = 0;
    };
    std::map<std::string, Run> runs;
    std::map<std::string, std::string> devices, drivers, versions;   // per API, for the run's row
    for (const auto& r : doc["runs"]) {
        Run run;
        const json& dev = r.contains("device") ? r["device"] : json();
        run.device = text(dev, "name");
        run.driver = text(dev, "driver");
        run.apiVersion = text(dev, "api_version");
        // readResultsJson checked its type.
        run.software = dev.is_object() && dev.contains("software_renderer") && dev["software_renderer"] == true;
        run.mode = text(r.contains("timing") ? r["timing"] : json(), "mode");
        const json& clocks = r.contains("gpu_clocks") ? r["gpu_clocks"] : json();
        auto median = [&](const char* key) { return number(clocks.is_object() && clocks.contains(key) ? clocks[key] : json(), "median"); };
        run.smMhz = median("sm_mhz");
        run.memMhz = median("mem_mhz");
        const std::string api = text(r, "backend");
        devices[api] = run.device;
        drivers[api] = run.driver;
        versions[api] = run.apiVersion;
        runs[text(r, "id")] = run;
    }
    auto joined = [](const std::map<std::string, std::string>& m) {
        std::string s;
        for (const auto& [api, v] : m) s += (s.empty() ? "" : "; ") + api + ": " + v;
        return s;
    };
    out.device = joined(devices);
    out.driver = joined(drivers);
    out.api = joined(versions);
    addSets(sets, out, [&](PassSeries& s) {
        const Run& r = runs[s.configId];
        s.device = r.device;
        s.timingMode = r.mode;
        s.softwareRenderer = r.software;
        for (auto& x : s.samples) x.smMhz = r.smMhz, x.memMhz = r.memMhz;
    });
    return {};
}

Status readGate(const json& doc, RunFile& out) {
    CAVITY_ASSIGN(const auto run, gate::fromJson(doc, out.path));
    out.format = "cavity-gate";
    std::map<std::tuple<std::string, std::string, std::string>, size_t> at;
    for (const auto& r : run.results) {
        if (out.device.empty()) {
            out.device = r.device;
            out.driver = r.driver;
        }
        for (const auto& t : r.timings) {
            const auto key = std::make_tuple(r.id, t.pass, r.device);
            auto it = at.find(key);
            if (it == at.end()) {
                PassSeries s;
                s.configId = r.id;
                s.pass = t.pass;
                s.device = r.device;
                s.api = apiOfId(r.id);
                s.clock = t.clock;
                // Budgets are advisory on a software renderer (unless enforced): either says so.
                s.softwareRenderer = t.advisory || looksSoftware(r.device);
                it = at.emplace(key, out.series.size()).first;
                out.series.push_back(std::move(s));
            }
            auto& s = out.series[it->second];
            if (s.clock != t.clock) s.clock = "mixed";
            // The gate's time of a pass is its median over the frames of one repetition.
            s.samples.push_back({int(s.samples.size()), t.medianMs, 0.0, 0.0});
        }
    }
    return {};
}

}  // namespace cavity::history
