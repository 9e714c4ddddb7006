#include "compare/sample_sets.h"

#include "core/json_input.h"
#include "measure/results.h"

#include <algorithm>
#include <cmath>

namespace cavity::compare {

using nlohmann::json;

void SampleSet::add(double value, const std::string& sampleClock, double sampleSmMhz) {
    if (ms.empty()) clock = sampleClock;
    else if (clock != sampleClock) {
        mixedClocks = true;
        clock = "mixed";
    }
    ms.push_back(value);
    smMhz.push_back(sampleSmMhz > 0 && std::isfinite(sampleSmMhz) ? sampleSmMhz : NAN);
    clocks.push_back(sampleClock);
}

SampleSet SampleSet::onClock(const std::string& c) const {
    SampleSet s;
    for (size_t i = 0; i < ms.size(); ++i)
        if (clocks[i] == c) s.add(ms[i], c, smMhz[i]);
    return s;
}

bool SampleSet::smClockKnown() const {
    return !smMhz.empty() && std::all_of(smMhz.begin(), smMhz.end(), [](double m) { return std::isfinite(m); });
}

SampleSet& SampleSets::at(const std::string& id, const std::string& pass) {
    auto key = std::make_pair(id, pass);
    auto it = series.find(key);
    if (it == series.end()) {
        order.push_back(key);
        it = series.emplace(std::move(key), SampleSet{}).first;
    }
    return it->second;
}

namespace {

// Numbers only: results.json writes a sample that was NaN as null, and a
// sample that was never a time tells nothing about the change. A series with
// no time at all would compare as a fall to nothing, so it is bad input.
Status addSamples(SampleSet& s, const JsonObject& owner, const std::string& clock, double smMhz, bool everySample) {
    CAVITY_ASSIGN(const auto samples, owner.numbers("samples_ms", 0, measure::kMaxRecordedMs, !everySample));
    size_t added = 0;
    for (double v : samples)
        if (std::isfinite(v)) {
            s.add(v, clock, smMhz);
            ++added;
        }
    if (!added) return owner.bad("samples_ms", "holds no time (a run needs at least one finite sample)");
    return {};
}

}  // namespace

Result<SampleSets> readResultsJson(const json& doc, const std::string& path, bool everySample) {
    SampleSets out;
    out.path = path;
    out.format = "cavity-results";
    CAVITY_ASSIGN(const JsonObject top, JsonObject::of(path, "", doc));
    CAVITY_ASSIGN(const auto runs, top.objects("runs"));
    for (const auto& r : runs) {
        CAVITY_ASSIGN(const std::string id, r.str("id"));
        CAVITY_ASSIGN(const std::string clock, r.str("clock"));
        // The clock decides whether two runs' times compare (a GPU's
        // timestamps against a wall clock do not): only the two cavity writes.
        if (clock != "gpu-timestamp" && clock != "wall")
            return badInput(path + ": runs '" + id + "': clock '" + clock + "' (gpu-timestamp or wall)");
        if (r.has("device")) {
            CAVITY_ASSIGN(const JsonObject device, r.object("device"));
            if (device.has("software_renderer")) {
                CAVITY_ASSIGN(const bool software, device.boolean("software_renderer"));
                out.softwareRenderer |= software;
            }
        }
        // The run's median SM clock, where NVML read one (gpu_clocks is null otherwise).
        double smMhz = NAN;
        const json& clocks = r.raw().contains("gpu_clocks") ? r.raw()["gpu_clocks"] : json();
        if (clocks.is_object() && clocks.contains("sm_mhz") && clocks["sm_mhz"].is_object() &&
            clocks["sm_mhz"].contains("median") && clocks["sm_mhz"]["median"].is_number())
            smMhz = clocks["sm_mhz"]["median"].get<double>();
        // The frame first, as a table reads best whole before parts.
        CAVITY_ASSIGN(const JsonObject frame, r.object("frame"));
        CAVITY_TRY(addSamples(out.at(id, kFramePass), frame, clock, smMhz, everySample));
        // The AO pipeline, cavity_bench's total (results.json of older runs has none).
        if (r.raw().contains(kPipelinePass)) {
            CAVITY_ASSIGN(const JsonObject pipeline, r.object(kPipelinePass));
            CAVITY_TRY(addSamples(out.at(id, kPipelinePass), pipeline, clock, smMhz, everySample));
        }
        CAVITY_ASSIGN(const auto passes, r.objects("passes"));
        for (const auto& p : passes) {
            CAVITY_ASSIGN(const std::string name, p.str("name"));
            CAVITY_TRY(addSamples(out.at(id, name), p, clock, smMhz, everySample));
        }
    }
    return out;
}

Result<SampleSets> loadSampleSets(const std::string& path) {
    CAVITY_ASSIGN(const json doc, readJsonFile(path));
    if (doc.is_object() && doc.contains("schema") && doc["schema"] == kResultsSchema) return readResultsJson(doc, path);
    if (doc.is_object() && doc.contains("benchmarks") && doc["benchmarks"].is_array())
        return readBenchmarkJson(doc, path);
    return badInput(path + ": neither a cavity results.json (schema " + kResultsSchema +
                    ") nor Google Benchmark JSON (benchmarks[])");
}

}  // namespace cavity::compare