#include "gate.h"

#include "image_io.h"
#include "runner.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>

namespace cavity::gate {

namespace fs = std::filesystem;
using nlohmann::json;

bool ConfigResult::imagesPassed() const {
    for (const auto& i : images)
        if (!i.passed()) return false;
    return true;
}

bool ConfigResult::timingPassed() const {
    for (const auto& t : timings)
        if (!t.passed()) return false;
    return true;
}

int GateRun::exitCode() const {
    bool bad = false, backend = !backendErrors.empty(), regression = false;
    for (const auto& r : results) {
        bad |= r.errorCode == 2;
        backend |= r.errorCode == 3;
        regression |= !r.passed();
    }
    return bad ? 2 : backend ? 3 : regression ? 1 : 0;
}

bool inShard(size_t index, int shardIndex, int shardCount) {
    return shardCount <= 1 || int(index % size_t(shardCount)) == shardIndex;
}

namespace {

std::string fmt(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", x);
    return b;
}

std::vector<std::string> judge(const metrics::Report& m, const Tolerance& t, bool perceptual) {
    std::vector<std::string> f;
    if (m.nonFinite > 0)
        f.push_back(std::to_string(m.nonFinite) + " non-finite pixels, first at (" + std::to_string(m.firstNonFiniteX) +
                    "," + std::to_string(m.firstNonFiniteY) + ")");
    if (m.maxAbs > t.maxAbs) f.push_back("max abs error " + fmt(m.maxAbs) + " > " + fmt(t.maxAbs) + " at (" +
                                         std::to_string(m.worstX) + "," + std::to_string(m.worstY) + ")");
    if (m.meanAbs > t.meanAbs) f.push_back("mean abs error " + fmt(m.meanAbs) + " > " + fmt(t.meanAbs));
    if (m.rmse > t.rmse) f.push_back("RMSE " + fmt(m.rmse) + " > " + fmt(t.rmse));
    if (m.psnr < t.psnrMin) f.push_back("PSNR " + fmt(m.psnr) + " dB < " + fmt(t.psnrMin) + " dB");
    if (m.overThresholdShare > t.overThresholdShare)
        f.push_back(fmt(100 * m.overThresholdShare) + "% of pixels over " + fmt(t.pixelThreshold) + " > " +
                    fmt(100 * t.overThresholdShare) + "%");
    if (m.ssim < t.ssimMin) f.push_back("SSIM " + fmt(m.ssim) + " < " + fmt(t.ssimMin));
    if (perceptual && m.flipMean > t.flipMeanMax) f.push_back("FLIP mean " + fmt(m.flipMean) + " > " + fmt(t.flipMeanMax));
    return f;
}

int expectedChannels(const std::string& image) { return image == "color" ? 4 : 1; }

// A baseline that exists must be readable and of the configuration's shape.
Status checkBaseline(const std::string& path, const RunConfig& c, const std::string& image) {
    if (!fs::exists(path)) return {};
    CAVITY_ASSIGN(HostImage b, readImage(path));
    const int ch = expectedChannels(image);
    // The raw AO of a half-resolution configuration is half the size.
    const bool half = c.half && image == "ao";
    const int w = half ? (c.width + 1) / 2 : c.width, h = half ? (c.height + 1) / 2 : c.height;
    if (b.width != w || b.height != h || b.channels != ch)
        return badInput(path + ": baseline is " + std::to_string(b.width) + "x" + std::to_string(b.height) + "x" +
                        std::to_string(b.channels) + ", configuration needs " + std::to_string(w) + "x" +
                        std::to_string(h) + "x" + std::to_string(ch));
    return {};
}

}  // namespace

Result<GateRun> runGate(const GateOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    const fs::path root(o.baselines);
    CAVITY_ASSIGN(Matrix matrix, loadMatrix((root / "matrices.json").string(), o.matrix));
    CAVITY_ASSIGN(Manifest manifest, loadManifest((root / "manifest.json").string()));
    CAVITY_ASSIGN(Budgets budgets, loadBudgets((root / "budgets.json").string()));
    std::optional<std::regex> filter;
    if (!o.filter.empty()) {
        try {
            filter.emplace(o.filter);
        } catch (const std::regex_error& e) {
            return badInput("--filter " + o.filter + ": not a regular expression (" + e.what() + ")");
        }
    }
    std::vector<RunConfig> configs;
    const auto all = matrix.expand();
    for (size_t i = 0; i < all.size(); ++i)
        if (inShard(i, o.shardIndex, o.shardCount) && (!filter || std::regex_search(configId(all[i]), *filter)))
            configs.push_back(all[i]);
    for (const auto& c : configs)
        for (const auto& img : checkedImages())
            CAVITY_TRY(checkBaseline((root / "images" / baselineKey(c) / (img.name + img.extension)).string(), c, img.name));
    CAVITY_TRY(checkWritableDir("--out", o.out));

    GateRun run;
    run.matrix = o.matrix;
    run.shardIndex = o.shardIndex;
    run.shardCount = o.shardCount;
    const fs::path out(o.out);
    for (auto api : {gpu::Api::OpenGL, gpu::Api::Vulkan}) {
        std::vector<const RunConfig*> mine;
        for (const auto& c : configs)
            if (c.api == api) mine.push_back(&c);
        if (mine.empty()) continue;
        gpu::BackendOptions bo;
        bo.deviceIndex = o.device;
        bo.validation = o.validation;
        auto backend = gpu::createBackend(api, bo);
        if (!backend) {
            run.backendErrors.push_back(backend.error().message);
            for (const auto* c : mine) {
                ConfigResult r;
                r.id = configId(*c);
                r.key = baselineKey(*c);
                r.config = *c;
                r.error = backend.error().message;
                r.errorCode = 3;
                run.results.push_back(std::move(r));
            }
            continue;
        }
        gpu::Backend& gpu = **backend;
        for (const auto* c : mine) {
            ConfigResult r;
            r.id = configId(*c);
            r.key = baselineKey(*c);
            r.config = *c;
            r.device = gpu.info().deviceName;
            RunOptions ro;
            ro.frames = matrix.frames;
            ro.warmup = matrix.warmup;
            ro.keepImages = true;
            ro.checkDeterminism = true;
            ro.overrides = o.overrides;
            auto rec = runConfig(gpu, *c, ro);
            if (!rec) {
                r.error = rec.error().message;
                r.errorCode = int(rec.error().code);
                run.results.push_back(std::move(r));
                continue;
            }
            r.deterministic = rec->deterministic;
            const Tolerance tol = manifest.forPipeline(c->kernel, r.device);
            const fs::path dir = out / "images" / r.id;
            std::error_code ec;
            fs::create_directories(dir, ec);
            for (const auto& ci : checkedImages()) {
                ImageCheck check;
                check.image = ci.name;
                check.tolerance = tol;
                const fs::path basePath = root / "images" / r.key / (ci.name + ci.extension);
                check.baseline = basePath.string();
                const HostImage& now = rec->pixels.at(ci.name);
                check.newExact = (dir / (ci.name + ".new" + ci.extension)).string();
                check.newPng = (dir / (ci.name + ".new.png")).string();
                CAVITY_TRY(writeImage(check.newExact, now));
                if (ci.extension != ".png") CAVITY_TRY(writeImage(check.newPng, now));
                if (!fs::exists(basePath)) {
                    check.failures.push_back("baseline missing: " + basePath.string() +
                                             " (accept the new image with `cavity baselines update`)");
                    r.errorCode = 2;
                } else {
                    CAVITY_ASSIGN(HostImage base, readImage(basePath.string()));
                    metrics::Options mo;
                    mo.threshold = tol.pixelThreshold;
                    mo.flip = ci.perceptual;
                    CAVITY_ASSIGN(check.metrics, metrics::compare(base, now, mo));
                    check.failures = judge(*check.metrics, tol, ci.perceptual);
                    check.baselinePng = (dir / (ci.name + ".baseline.png")).string();
                    check.diffPng = (dir / (ci.name + ".diff.png")).string();
                    CAVITY_TRY(writeImage(check.baselinePng, base));
                    CAVITY_TRY(writeImage(check.diffPng, metrics::heatmap(base, now, 2 * tol.pixelThreshold)));
                }
                r.images.push_back(std::move(check));
            }
            for (const auto& p : rec->timing.passes) {
                TimingCheck t;
                t.pass = p.name;
                t.medianMs = p.stats.median;
                t.clock = rec->timing.clock;
                t.budgetMs = budgets.find(r.device, r.id, p.name);
                r.timings.push_back(t);
            }
            std::fprintf(stderr, "gate: %-56s %s\n", r.id.c_str(), r.passed() ? "pass" : "FAIL");
            run.results.push_back(std::move(r));
        }
    }
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

// ---- gate.json ----

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
            images.push_back({{"image", i.image}, {"baseline", i.baseline}, {"new", i.newExact}, {"new_png", i.newPng},
                              {"baseline_png", i.baselinePng}, {"diff_png", i.diffPng}, {"metrics", m},
                              {"tolerance", toJson(i.tolerance)}, {"failures", i.failures}, {"passed", i.passed()}});
        }
        json timings = json::array();
        for (const auto& t : r.timings)
            timings.push_back({{"pass", t.pass}, {"median_ms", t.medianMs}, {"clock", t.clock},
                               {"budget_ms", t.budgetMs ? json(*t.budgetMs) : json(nullptr)}, {"passed", t.passed()}});
        results.push_back({{"id", r.id}, {"baseline_key", r.key}, {"device", r.device}, {"kernel", r.config.kernel},
                           {"passed", r.passed()}, {"deterministic", r.deterministic}, {"error", r.error},
                           {"error_code", r.errorCode}, {"images", images}, {"timings", timings}});
    }
    return {{"schema", "cavity.gate/1"}, {"matrix", run.matrix}, {"shard", {run.shardIndex, run.shardCount}},
            {"seconds", run.seconds}, {"exit_code", run.exitCode()}, {"backend_errors", run.backendErrors},
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
            r.key = rj.at("baseline_key");
            r.device = rj.at("device");
            r.config.kernel = rj.at("kernel");
            r.deterministic = rj.at("deterministic");
            r.error = rj.at("error");
            r.errorCode = rj.at("error_code");
            for (const auto& ij : rj.at("images")) {
                ImageCheck i;
                i.image = ij.at("image");
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
