#include "sample_sets.h"

#include "json_file.h"
#include "results.h"

namespace cavity {

using nlohmann::json;

void SampleSet::add(double value, const std::string& sampleClock) {
    if (ms.empty()) clock = sampleClock;
    else if (clock != sampleClock) {
        mixedClocks = true;
        clock = "mixed";
    }
    ms.push_back(value);
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
// sample that was never a time tells nothing about the change.
void addSamples(SampleSet& s, const json& samples, const std::string& clock) {
    for (const auto& v : samples)
        if (v.is_number()) s.add(v.get<double>(), clock);
}

}  // namespace

Result<SampleSets> readResultsJson(const json& doc, const std::string& path) {
    SampleSets out;
    out.path = path;
    out.format = "cavity-results";
    const json& runs = doc.contains("runs") ? doc["runs"] : json();
    if (!runs.is_array()) return badInput(path + ": runs: must be an array (schema cavity.results/1)");
    for (size_t i = 0; i < runs.size(); ++i) {
        const std::string where = path + ": runs[" + std::to_string(i) + "]";
        try {
            const json& r = runs[i];
            const std::string id = r.at("id");
            const std::string clock = r.at("clock");
            // The frame first, as a table reads best whole before parts.
            addSamples(out.at(id, kFramePass), r.at("frame").at("samples_ms"), clock);
            for (const auto& p : r.at("passes"))
                addSamples(out.at(id, p.at("name").get<std::string>()), p.at("samples_ms"), clock);
        } catch (const json::exception& e) {
            return badInput(where + ": malformed run: " + e.what());
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

}  // namespace cavity
