// gate.json ("cavity.gate/1"): the verdicts `gate merge` joins and
// `baselines update` accepts from.
#include "gate/namespace.h"
#include "gate/gate.h"
#include "render/render_manifest.h"
#include "core/json_input.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

namespace cavity::gate {

using nlohmann::json;

json toleranceJson(const Tolerance& t) {
    return {{"max_abs", t.maxAbs}, {"mean_abs", t.meanAbs}, {"rmse", t.rmse}, {"psnr_min", t.psnrMin},
            {"pixel_threshold", t.pixelThreshold}, {"over_threshold_share", t.overThresholdShare},
            {"ssim_min", t.ssimMin}, {"flip_mean_max", t.flipMeanMax}, {"differing_delta", t.differingDelta},
            {"differing_share_max", t.differingShareMax}, {"sized_for_pixels", t.sizedForPixels}};
}

namespace {

double num(double x) { return std::isfinite(x) ? x : (x > 0 ? 1e300 : -1e300); }

}  // namespace

json metricsJson(const metrics::Report& m) {
    return {{"max_abs", num(m.maxAbs)}, {"mean_abs", num(m.meanAbs)}, {"rmse", num(m.rmse)},
            {"psnr", num(m.psnr)}, {"over_threshold_share", m.overThresholdShare},
            {"ssim", m.ssim}, {"flip_mean", m.flipMean},
            {"non_finite", m.nonFinite}, {"differing_pixels", m.differingPixels},
            {"differing_share", m.differingShare}, {"channels_compared", m.channelsCompared}};
}

json toJson(const GateRun& run) {
    json results = json::array();
    for (const auto& r : run.results) {
        json images = json::array();
        for (const auto& i : r.images) {
            const json m = i.metrics ? metricsJson(*i.metrics) : json(nullptr);
            images.push_back({{"image", i.image}, {"digest", i.digest}, {"route", i.route}, {"approval", i.approval}, {"reference", i.reference},
                              {"baseline", i.baseline}, {"new", i.newExact}, {"new_png", i.newPng},
                              {"baseline_png", i.baselinePng}, {"diff_png", i.diffPng}, {"metrics", m},
                              {"tolerance", toleranceJson(i.tolerance)}, {"failures", i.failures}, {"passed", i.passed()}});
        }
        json timings = json::array();
        for (const auto& t : r.timings)
            timings.push_back({{"pass", t.pass}, {"median_ms", t.medianMs}, {"clock", t.clock},
                               {"ci_low_ms", std::isfinite(t.lowMs) ? json(t.lowMs) : json()},
                               {"ci_high_ms", std::isfinite(t.highMs) ? json(t.highMs) : json()},
                               {"budget_ms", t.budgetMs ? json(*t.budgetMs) : json(nullptr)}, {"advisory", t.advisory},
                               {"within_budget", t.withinBudget()}, {"passed", t.passed()}});
        results.push_back({{"id", r.id}, {"repetition", r.repetition}, {"baseline_key", r.key}, {"device", r.device}, {"driver", r.driver}, {"kernel", r.config.kernel},
                           {"passed", r.passed()}, {"verdict", r.verdict()}, {"fatal", r.fatal()}, {"attempts", r.attempts},
                           {"first_failures", r.firstFailures}, {"expected", r.expected}, {"expected_reason", r.expectedWhy},
                           {"deterministic", r.deterministic}, {"error", r.error},
                           {"error_code", r.errorCode}, {"images", images}, {"timings", timings}});
    }
    // How many configurations the results hold, so that a reader finds
    // results lost from a damaged or hand-edited file (fromJson).
    std::set<std::string> ids;
    for (const auto& r : run.results) ids.insert(r.id);
    return {{"schema", "cavity.gate/1"}, {"matrix", run.matrix}, {"filter", run.filter}, {"configurations", ids.size()},
            {"shard", {run.shardIndex, run.shardCount}}, {"strict", run.strict},
            {"seconds", run.seconds}, {"render_seconds", run.renderSeconds}, {"exit_code", run.exitCode()}, {"counts", run.counts()},
            {"backend_errors", run.backendErrors}, {"kernel_sources", render::replacedJson(run.replaced)},
            {"kernel_packages", measure::packagesJson(run.packages)},
            {"results", results}};
}

namespace {

constexpr double kAny = 1e300;   // gate.json writes a non-finite metric as +-1e300 (num() above)

Result<Tolerance> readTolerance(const JsonObject& t) {
    Tolerance out;
    CAVITY_ASSIGN(out.maxAbs, t.number("max_abs", 0, kAny));
    CAVITY_ASSIGN(out.meanAbs, t.number("mean_abs", 0, kAny));
    CAVITY_ASSIGN(out.rmse, t.number("rmse", 0, kAny));
    CAVITY_ASSIGN(out.psnrMin, t.number("psnr_min", -kAny, kAny));
    CAVITY_ASSIGN(out.pixelThreshold, t.number("pixel_threshold", 0, kAny));
    CAVITY_ASSIGN(out.overThresholdShare, t.number("over_threshold_share", 0, kAny));
    CAVITY_ASSIGN(out.ssimMin, t.number("ssim_min", -kAny, kAny));
    CAVITY_ASSIGN(out.flipMeanMax, t.number("flip_mean_max", 0, kAny));
    // Absent from gate.json files written before the differing-pixel count.
    CAVITY_ASSIGN(out.differingDelta, t.number("differing_delta", 0, 255, 0));
    CAVITY_ASSIGN(out.differingShareMax, t.number("differing_share_max", 0, 1, 1));
    // Absent from gate.json files written before tolerances were sized.
    CAVITY_ASSIGN(out.sizedForPixels, t.number("sized_for_pixels", 0, kAny, 0));
    return out;
}

Result<metrics::Report> readMetrics(const JsonObject& m) {
    metrics::Report rep{};
    CAVITY_ASSIGN(rep.maxAbs, m.number("max_abs", 0, kAny));
    CAVITY_ASSIGN(rep.meanAbs, m.number("mean_abs", 0, kAny));
    CAVITY_ASSIGN(rep.rmse, m.number("rmse", 0, kAny));
    CAVITY_ASSIGN(rep.psnr, m.number("psnr", -kAny, kAny));
    CAVITY_ASSIGN(rep.overThresholdShare, m.number("over_threshold_share", 0, 1));
    CAVITY_ASSIGN(rep.ssim, m.number("ssim", -kAny, kAny));
    CAVITY_ASSIGN(rep.flipMean, m.number("flip_mean", -1, kAny));
    CAVITY_ASSIGN(const double nonFinite, m.number("non_finite", 0, 1e18));
    rep.nonFinite = (long long)nonFinite;
    CAVITY_ASSIGN(const double differing, m.number("differing_pixels", 0, 1e18, 0));
    rep.differingPixels = (long long)differing;
    CAVITY_ASSIGN(rep.differingShare, m.number("differing_share", 0, 1, 0));
    CAVITY_ASSIGN(rep.channelsCompared, m.integer("channels_compared", 0, 4, 0));
    return rep;
}

Result<ImageCheck> readImageCheck(const JsonObject& ij) {
    ImageCheck i;
    CAVITY_ASSIGN(i.image, ij.str("image"));
    CAVITY_ASSIGN(i.digest, ij.str("digest", ""));
    // Absent before approvals: every image was judged by tolerance.
    CAVITY_ASSIGN(i.route, ij.str("route", "tolerance"));
    if (i.route != "tolerance" && i.route != "digest" && i.route != "negative")
        return ij.bad("route", "must be tolerance, digest or negative");
    CAVITY_ASSIGN(i.approval, ij.str("approval", ""));
    CAVITY_ASSIGN(i.reference, ij.str("reference", ""));
    CAVITY_ASSIGN(i.baseline, ij.str("baseline"));
    CAVITY_ASSIGN(i.newExact, ij.str("new"));
    CAVITY_ASSIGN(i.newPng, ij.str("new_png"));
    CAVITY_ASSIGN(i.baselinePng, ij.str("baseline_png"));
    CAVITY_ASSIGN(i.diffPng, ij.str("diff_png"));
    CAVITY_ASSIGN(i.failures, ij.strings("failures"));
    CAVITY_ASSIGN(const JsonObject t, ij.object("tolerance"));
    CAVITY_ASSIGN(i.tolerance, readTolerance(t));
    if (!ij.has("metrics")) return ij.bad("metrics", "missing");
    if (!ij.raw()["metrics"].is_null()) {
        CAVITY_ASSIGN(const JsonObject m, ij.object("metrics"));
        CAVITY_ASSIGN(i.metrics, readMetrics(m));
    }
    return i;
}

Result<ConfigResult> readResult(const JsonObject& rj) {
    ConfigResult r;
    CAVITY_ASSIGN(r.id, rj.str("id"));
    CAVITY_ASSIGN(r.repetition, rj.integer("repetition", 0, 1 << 20, 0));   // absent before cavity_render --repeat
    CAVITY_ASSIGN(r.key, rj.str("baseline_key"));
    CAVITY_ASSIGN(r.device, rj.str("device"));
    CAVITY_ASSIGN(r.driver, rj.str("driver", ""));
    CAVITY_ASSIGN(r.config.kernel, rj.str("kernel"));
    CAVITY_ASSIGN(r.deterministic, rj.boolean("deterministic"));
    CAVITY_ASSIGN(r.error, rj.str("error"));
    CAVITY_ASSIGN(r.errorCode, rj.integer("error_code", 0, 255));
    // Absent before retries and expectations: one attempt, none listed.
    CAVITY_ASSIGN(r.attempts, rj.integer("attempts", 1, 1000, 1));
    if (rj.has("first_failures")) {
        CAVITY_ASSIGN(r.firstFailures, rj.strings("first_failures"));
    }
    CAVITY_ASSIGN(r.expected, rj.str("expected", ""));
    CAVITY_ASSIGN(r.expectedWhy, rj.str("expected_reason", ""));
    CAVITY_ASSIGN(const auto images, rj.objects("images"));
    for (const auto& ij : images) {
        CAVITY_ASSIGN(auto i, readImageCheck(ij));
        r.images.push_back(std::move(i));
    }
    CAVITY_ASSIGN(const auto timings, rj.objects("timings"));
    for (const auto& tj : timings) {
        TimingCheck t;
        CAVITY_ASSIGN(t.pass, tj.str("pass"));
        CAVITY_ASSIGN(t.medianMs, tj.number("median_ms", 0, kAny));
        CAVITY_ASSIGN(t.clock, tj.str("clock"));
        CAVITY_ASSIGN(t.budgetMs, tj.numberOrNull("budget_ms", 0, kAny));
        // The median's interval: absent before it was recorded, null with too few frames.
        for (auto [key, field] : {std::pair{"ci_low_ms", &t.lowMs}, std::pair{"ci_high_ms", &t.highMs}})
            if (tj.has(key)) {
                CAVITY_ASSIGN(const auto v, tj.numberOrNull(key, 0, kAny));
                *field = v ? *v : NAN;
            }
        // Absent before software renderers' budgets were advisory: every budget failed.
        if (tj.has("advisory")) {
            CAVITY_ASSIGN(t.advisory, tj.boolean("advisory"));
        }
        r.timings.push_back(t);
    }
    // The verdict is recomputed from the above; one written that is no
    // verdict at all is a damaged file, not a detail to pass over.
    if (rj.has("verdict")) {
        CAVITY_ASSIGN(const std::string v, rj.str("verdict"));
        if (std::find(std::begin(kVerdicts), std::end(kVerdicts), v) == std::end(kVerdicts)) {
            std::string names;
            for (const char* k : kVerdicts) names += (names.empty() ? "" : ", ") + std::string(k);
            return rj.bad("verdict", "must be one of " + names);
        }
    }
    return r;
}

}  // namespace

Result<metrics::Report> metricsFromJson(const json& j, const std::string& where) {
    CAVITY_ASSIGN(const JsonObject m, JsonObject::of(where, "metrics", j));
    return readMetrics(m);
}

Result<GateRun> fromJson(const json& j, const std::string& path) {
    if (!j.is_object() || !j.contains("schema") || j["schema"] != "cavity.gate/1")
        return badInput(path + ": not a cavity gate.json (schema cavity.gate/1)");
    CAVITY_ASSIGN(const JsonObject top, JsonObject::of(path, "", j));
    GateRun run;
    CAVITY_ASSIGN(run.matrix, top.str("matrix"));
    CAVITY_ASSIGN(const auto shard, top.integers("shard", 0, 1 << 20));
    if (shard.size() != 2 || shard[1] < 1 || shard[0] >= shard[1]) return top.bad("shard", "must be [I, N] with 0 <= I < N");
    run.shardIndex = shard[0];
    run.shardCount = shard[1];
    if (top.has("strict")) {   // absent before --strict existed: tolerance-based
        CAVITY_ASSIGN(run.strict, top.boolean("strict"));
    }
    CAVITY_ASSIGN(run.seconds, top.number("seconds", 0, kAny));
    CAVITY_ASSIGN(run.renderSeconds, top.number("render_seconds", 0, kAny, 0.0));
    CAVITY_ASSIGN(run.backendErrors, top.strings("backend_errors"));
    // Absent before --kernel-source was recorded: nothing replaced.
    if (top.has("kernel_sources")) {
        CAVITY_ASSIGN(run.replaced, render::parseReplaced(top.raw()["kernel_sources"], path));
    }
    if (top.has("kernel_packages")) {   // absent before packages were recorded
        CAVITY_ASSIGN(run.packages, measure::parsePackages(top.raw()["kernel_packages"], path));
    }
    CAVITY_ASSIGN(run.filter, top.str("filter", ""));   // absent before shards were checked: all
    CAVITY_ASSIGN(const auto results, top.objects("results"));
    std::set<std::string> ids;
    for (const auto& rj : results) {
        CAVITY_ASSIGN(auto r, readResult(rj));
        ids.insert(r.id);
        run.results.push_back(std::move(r));
    }
    if (top.has("configurations")) {
        CAVITY_ASSIGN(const int count, top.integer("configurations", 0, 1 << 30));
        if (size_t(count) != ids.size())
            return top.bad("configurations", "the results hold " + std::to_string(ids.size()) +
                                                 " configurations (the file lost some, or was edited)");
    }
    return run;
}

}  // namespace cavity::gate
