// gate.json ("cavity.gate/1"): the verdicts `gate merge` joins and
// `baselines update` accepts from.
#include "gate.h"

#include <cmath>

namespace cavity::gate {

using nlohmann::json;

namespace {

json toJson(const Tolerance& t) {
    return {{"max_abs", t.maxAbs}, {"mean_abs", t.meanAbs}, {"rmse", t.rmse}, {"psnr_min", t.psnrMin},
            {"pixel_threshold", t.pixelThreshold}, {"over_threshold_share", t.overThresholdShare},
            {"ssim_min", t.ssimMin}, {"flip_mean_max", t.flipMeanMax}};
}

double num(double x) { return std::isfinite(x) ? x : (x > 0 ? 1e300 : -1e300); }

}  // namespace

json toJson(const GateRun& run) {
    json results = json::array();
    for (const auto& r : run.results) {
        json images = json::array();
        for (const auto& i : r.images) {
            json m = nullptr;
            if (i.metrics)
                m = {{"max_abs", num(i.metrics->maxAbs)}, {"mean_abs", num(i.metrics->meanAbs)}, {"rmse", num(i.metrics->rmse)},
                     {"psnr", num(i.metrics->psnr)}, {"over_threshold_share", i.metrics->overThresholdShare},
                     {"ssim", i.metrics->ssim}, {"flip_mean", i.metrics->flipMean},
                     {"non_finite", i.metrics->nonFinite}};
            images.push_back({{"image", i.image}, {"digest", i.digest}, {"baseline", i.baseline}, {"new", i.newExact}, {"new_png", i.newPng},
                              {"baseline_png", i.baselinePng}, {"diff_png", i.diffPng}, {"metrics", m},
                              {"tolerance", toJson(i.tolerance)}, {"failures", i.failures}, {"passed", i.passed()}});
        }
        json timings = json::array();
        for (const auto& t : r.timings)
            timings.push_back({{"pass", t.pass}, {"median_ms", t.medianMs}, {"clock", t.clock},
                               {"budget_ms", t.budgetMs ? json(*t.budgetMs) : json(nullptr)}, {"passed", t.passed()}});
        results.push_back({{"id", r.id}, {"repetition", r.repetition}, {"baseline_key", r.key}, {"device", r.device}, {"kernel", r.config.kernel},
                           {"passed", r.passed()}, {"verdict", r.verdict()}, {"fatal", r.fatal()}, {"attempts", r.attempts},
                           {"first_failures", r.firstFailures}, {"expected", r.expected}, {"expected_reason", r.expectedWhy},
                           {"deterministic", r.deterministic}, {"error", r.error},
                           {"error_code", r.errorCode}, {"images", images}, {"timings", timings}});
    }
    return {{"schema", "cavity.gate/1"}, {"matrix", run.matrix}, {"shard", {run.shardIndex, run.shardCount}},
            {"seconds", run.seconds}, {"exit_code", run.exitCode()}, {"counts", run.counts()},
            {"backend_errors", run.backendErrors},
            {"results", results}};
}

Result<GateRun> fromJson(const json& j, const std::string& path) {
    if (!j.is_object() || j.value("schema", "") != "cavity.gate/1")
        return badInput(path + ": not a cavity gate.json (schema cavity.gate/1)");
    GateRun run;
    try {
        run.matrix = j.at("matrix");
        run.shardIndex = j.at("shard")[0];
        run.shardCount = j.at("shard")[1];
        run.seconds = j.at("seconds");
        run.backendErrors = j.at("backend_errors").get<std::vector<std::string>>();
        for (const auto& rj : j.at("results")) {
            ConfigResult r;
            r.id = rj.at("id");
            r.repetition = rj.value("repetition", 0);   // absent before cavity_render --repeat
            r.key = rj.at("baseline_key");
            r.device = rj.at("device");
            r.config.kernel = rj.at("kernel");
            r.deterministic = rj.at("deterministic");
            r.error = rj.at("error");
            r.errorCode = rj.at("error_code");
            // Absent before retries and expectations: one attempt, none listed.
            r.attempts = rj.value("attempts", 1);
            r.firstFailures = rj.value("first_failures", std::vector<std::string>{});
            r.expected = rj.value("expected", "");
            r.expectedWhy = rj.value("expected_reason", "");
            for (const auto& ij : rj.at("images")) {
                ImageCheck i;
                i.image = ij.at("image");
                i.digest = ij.value("digest", "");
                i.baseline = ij.at("baseline");
                i.newExact = ij.at("new");
                i.newPng = ij.at("new_png");
                i.baselinePng = ij.at("baseline_png");
                i.diffPng = ij.at("diff_png");
                i.failures = ij.at("failures").get<std::vector<std::string>>();
                const auto& t = ij.at("tolerance");
                i.tolerance = {t.at("max_abs"), t.at("mean_abs"), t.at("rmse"), t.at("psnr_min"),
                               t.at("pixel_threshold"), t.at("over_threshold_share"), t.at("ssim_min"),
                               t.at("flip_mean_max")};
                if (!ij.at("metrics").is_null()) {
                    const auto& m = ij.at("metrics");
                    metrics::Report rep{};
                    rep.maxAbs = m.at("max_abs");
                    rep.meanAbs = m.at("mean_abs");
                    rep.rmse = m.at("rmse");
                    rep.psnr = m.at("psnr");
                    rep.overThresholdShare = m.at("over_threshold_share");
                    rep.ssim = m.at("ssim");
                    rep.flipMean = m.at("flip_mean");
                    rep.nonFinite = m.at("non_finite");
                    i.metrics = rep;
                }
                r.images.push_back(std::move(i));
            }
            for (const auto& tj : rj.at("timings")) {
                TimingCheck t;
                t.pass = tj.at("pass");
                t.medianMs = tj.at("median_ms");
                t.clock = tj.at("clock");
                if (!tj.at("budget_ms").is_null()) t.budgetMs = tj.at("budget_ms").get<double>();
                r.timings.push_back(t);
            }
            run.results.push_back(std::move(r));
        }
    } catch (const json::exception& e) {
        return badInput(path + ": malformed gate.json: " + e.what());
    }
    return run;
}

}  // namespace cavity::gate
