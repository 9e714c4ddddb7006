#include "quality_recommend.h"

#include "compare/sample_sets.h"
#include "kernel.h"
#include "stats/stats.h"

#include <algorithm>
#include <regex>
#include <set>

namespace cavity::flags {

Result<std::map<std::pair<std::string, int>, double>> loadCosts(const std::string& path, bool half) {
    CAVITY_ASSIGN(const compare::SampleSets sets, compare::loadSampleSets(path));
    // At most 9 digits a number: std::stoi and std::stoll then cannot throw.
    static const std::regex id(R"(^[^/]+/([a-z_]+)/n(\d{1,9})/b\d+/(full|half)/(\d{1,9})x(\d{1,9})/(gl|vk)/(compute|fragment)$)");
    // id -> its pipeline time
    std::map<std::string, double> pipeline;
    for (const auto& [key, series] : sets.series) {
        if (series.ms.empty() || series.mixedClocks) continue;
        const double median = summarize(series.ms).median;
        if (sets.format == "google-benchmark") {
            if (key.second == compare::kPipelinePass) pipeline[key.first] = median;
        } else if (key.second != compare::kFramePass && key.second != "gbuffer") {
            pipeline[key.first] += median;
        }
    }
    // (kernel, samples) -> (pixels, times at that size)
    std::map<std::pair<std::string, int>, std::pair<long long, std::vector<double>>> found;
    for (const auto& [name, ms] : pipeline) {
        std::smatch m;
        if (!std::regex_match(name, m, id) || (m[3] == "half") != half) continue;
        const long long pixels = std::stoll(m[4]) * std::stoll(m[5]);
        auto& slot = found[{m[1], std::stoi(m[2])}];
        if (pixels > slot.first) slot = {pixels, {}};
        if (pixels == slot.first) slot.second.push_back(ms);
    }
    std::map<std::pair<std::string, int>, double> costs;
    for (const auto& [k, v] : found) costs[k] = summarize(v.second).median;
    if (costs.empty())
        return badInput("--cost " + path + ": no configuration of the form scene/kernel/nS/bB/" + (half ? "half" : "full") +
                        "/WxH/api/stage with a time");
    return costs;
}

Result<CostSource> costSource(const std::string& path, bool half) {
    CAVITY_ASSIGN(const compare::SampleSets sets, compare::loadSampleSets(path));
    static const std::regex id(R"(^[^/]+/[a-z_]+/n\d+/b\d+/(full|half)/(\d+x\d+)/(gl|vk)/(compute|fragment)$)");
    std::set<std::string> apis, stages, sizes, clocks;
    for (const auto& [key, series] : sets.series) {
        std::smatch m;
        if (series.ms.empty() || !std::regex_match(key.first, m, id) || (m[1] == "half") != half) continue;
        sizes.insert(m[2]);
        apis.insert(m[3]);
        stages.insert(m[4]);
        clocks.insert(series.clock == "wall" ? "host wall clock" : "GPU timestamps");
    }
    auto list = [](const std::set<std::string>& s) {
        std::string out;
        for (const auto& v : s) out += (out.empty() ? "" : ", ") + v;
        return out;
    };
    CostSource out;
    out.softwareRenderer = sets.softwareRenderer;
    out.text = "cost ms: the AO pipeline's median time (G-buffer left out) from " + path + ", over " + list(apis) + ", " +
               list(stages) + " at the largest of " + list(sizes) + ", on " + list(clocks) +
               (sets.softwareRenderer ? "; measured on a software renderer: the host CPU's time, not a GPU's" : "");
    return out;
}

std::vector<Candidate> candidates(const std::vector<QualityRow>& rows,
                                  const std::map<std::pair<std::string, int>, double>& costs) {
    std::map<std::pair<std::string, int>, std::pair<double, int>> sum;
    for (const auto& r : rows) {
        auto& s = sum[{r.kernel, r.samples}];
        s.first += r.meanAbsError;
        ++s.second;
    }
    std::vector<Candidate> out;
    for (const auto& [k, s] : sum) {
        Candidate c{k.first, k.second, s.first / s.second, std::nullopt, true};
        if (const auto cost = costs.find(k); cost != costs.end()) c.costMs = cost->second;
        if (const auto* d = kernels::find(k.first)) c.screenSpace = !kernels::evaluatesScene(*d);
        out.push_back(c);
    }
    std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.mae < b.mae; });
    return out;
}

std::vector<Candidate> paretoFront(const std::vector<Candidate>& all) {
    std::vector<Candidate> priced;
    for (const auto& c : all)
        if (c.screenSpace && c.costMs) priced.push_back(c);
    std::sort(priced.begin(), priced.end(), [](const Candidate& a, const Candidate& b) {
        return *a.costMs != *b.costMs ? *a.costMs < *b.costMs : a.mae < b.mae;
    });
    std::vector<Candidate> front;
    for (const auto& c : priced)
        if (front.empty() || c.mae < front.back().mae) front.push_back(c);
    return front;
}

std::optional<Candidate> bestWithin(const std::vector<Candidate>& all, double budgetMs) {
    std::optional<Candidate> best;
    for (const auto& c : all)
        if (c.screenSpace && c.costMs && *c.costMs <= budgetMs && (!best || c.mae < best->mae)) best = c;
    return best;
}

nlohmann::json candidateJson(const Candidate& c) {
    return {{"kernel", c.kernel}, {"samples", c.samples}, {"mae", c.mae},
            {"cost_ms", c.costMs ? nlohmann::json(*c.costMs) : nlohmann::json(nullptr)}, {"screen_space", c.screenSpace}};
}

}  // namespace cavity::flags
