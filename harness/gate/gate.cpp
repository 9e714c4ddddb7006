#include "gate/gate.h"

#include "core/progress.h"

#include "pipeline/config_id.h"
#include "core/digest.h"
#include "gate/expectations.h"
#include "gate/gate_judge.h"
#include "render/rendering.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>

namespace cavity::gate {

namespace fs = std::filesystem;

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

std::vector<std::string> ConfigResult::failureLines() const {
    std::vector<std::string> lines;
    if (!error.empty()) lines.push_back(error);
    for (const auto& i : images)
        for (const auto& f : i.failures) lines.push_back(i.image + ": " + f);
    for (const auto& t : timings)
        if (!t.passed()) {
            char b[128];
            std::snprintf(b, sizeof b, "time %s: median %.4g ms > budget %.4g ms", t.pass.c_str(), t.medianMs, *t.budgetMs);
            lines.push_back(b);
        }
    return lines;
}

bool ImageCheck::changed() const {
    if (route != "tolerance" || !metrics) return false;
    // An 8-bit image (the colour) arrives as floats, and a driver's readback
    // and the PNG reader need not turn step k into the same float k / 255:
    // they differ in the last bit. Only a whole step is a change of the
    // image, so an image accepted from this very render reads unchanged.
    const auto& all = checkedImages();
    const auto it = std::find_if(all.begin(), all.end(), [&](const CheckedImage& c) { return c.name == image; });
    const bool eightBit = it != all.end() && it->extension == ".png";
    return metrics->maxAbs > (eightBit ? 0.5 / 255.0 : 0.0);
}

bool ConfigResult::changed() const {
    return std::any_of(images.begin(), images.end(), [](const ImageCheck& i) { return i.changed(); });
}

std::string ConfigResult::verdict() const {
    if (!error.empty()) return "error";
    if (passed()) {
        if (attempts > 1) return "flaky";
        if (expected == "fail") return "unexpected-pass";
        return changed() ? "changed" : "pass";
    }
    if (expected == "fail") return "expected-fail";
    if (expected == "flake") return "known-flake";
    return "fail";
}

bool ConfigResult::fatal() const {
    const std::string v = verdict();
    return v == "fail" || v == "error" || v == "unexpected-pass";
}

int GateRun::exitCode() const {
    bool bad = false, backend = !backendErrors.empty(), regression = false, unreachable = false, corrupt = false;
    for (const auto& r : results) {
        bad |= r.errorCode == 2;
        backend |= r.errorCode == 3;
        unreachable |= r.errorCode == 5;
        corrupt |= r.errorCode == 6;
        regression |= r.fatal() || (strict && r.verdict() == "changed");
    }
    // A verdict the store could not back is no verdict: its code before a
    // backend's or a regression's.
    return bad ? 2 : corrupt ? 6 : unreachable ? 5 : backend ? 3 : regression ? 1 : 0;
}

void GateRun::applyStrict() {
    if (!strict) return;
    for (auto& r : results)
        for (auto& i : r.images)
            if (i.changed() && i.passed()) {
                char b[48];
                std::snprintf(b, sizeof b, "%.4g", i.metrics->maxAbs);
                i.failures.push_back(std::string("changed: max abs error ") + b +
                                     " (--strict: approve its digest to accept it)");
            }
}

std::map<std::string, int> GateRun::counts() const {
    std::map<std::string, int> c;
    for (const auto& r : results) ++c[r.verdict()];
    return c;
}

std::string ConfigResult::label() const {
    return repetition ? id + " (repetition " + std::to_string(repetition) + ")" : id;
}

namespace {

// The test hook's perturbation: the raw AO inverted, far past any
// tolerance, on the first attempt only.
void perturbForTest(render::Rendering& r) {
    const auto ao = r.images.find("ao");
    if (ao == r.images.end()) return;
    for (float& v : ao->second.pixels) v = 1.0f - v;
    r.digests["ao"] = imageDigest(ao->second);
    r.deterministic = false;   // what it stands for: a render that differs from run to run
}

// A failure another render could change: a time (noisy), or images from a
// render whose frames differed. Images of a deterministic render that
// failed fail again, bit for bit: retrying them only costs time.
bool worthRetrying(const ConfigResult& r) {
    return !r.passed() && r.error.empty() && r.errorCode == 0 && (r.imagesPassed() || !r.deterministic);
}

}  // namespace

void dropStaleReports(const std::string& out) {
    std::error_code ec;
    for (const char* name : kReportFiles) fs::remove(fs::path(out) / name, ec);
}

Result<GateRun> runGate(const GateOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    CAVITY_ASSIGN(Matrix matrix, loadMatrix((fs::path(o.baselines) / "matrices.json").string(), o.matrix));
    CAVITY_ASSIGN(auto entries, selectEntries(matrix, o.shardIndex, o.shardCount, o.filter));
    std::vector<RunConfig> configs;
    for (const auto& e : entries) configs.push_back(e.config);
    CAVITY_ASSIGN(Judge judge, prepareJudge(o.baselines, configs, o.out, o.store));
    judge.enforceCpuBudgets = o.enforceCpuBudgets;
    CAVITY_ASSIGN(const Expectations expectations,
                  loadExpectations(o.expectations.empty() ? (fs::path(o.baselines) / "expectations").string() : o.expectations));
    std::optional<std::regex> flaky;
    if (!o.flakyForTest.empty()) {
        try {
            flaky.emplace(o.flakyForTest);
        } catch (const std::regex_error&) {
            return badInput("CAVITY_TEST_FLAKY=" + o.flakyForTest + ": not a regular expression");
        }
    }

    CAVITY_TRY(checkSourcesUsed(o.replaced, configs));
    GateRun run;
    run.matrix = o.matrix;
    run.filter = o.filter;
    run.replaced = o.replaced;
    run.packages = measure::packagesLoaded();
    run.strict = o.strict;
    run.shardIndex = o.shardIndex;
    run.shardCount = o.shardCount;
    render::RenderOptions ro;
    ro.device = o.device;
    ro.validation = o.validation;
    ro.overrides = o.overrides;
    int attempt = 0;
    std::map<std::string, size_t> where;   // id -> index in run.results
    dropStaleReports(o.out);
    Progress progress(entries.size(), o.quiet, "gate: ");
    auto sink = [&](render::Rendering&& rendering) -> Status {
        if (attempt == 0 && flaky && std::regex_search(rendering.id, *flaky)) perturbForTest(rendering);
        CAVITY_ASSIGN(ConfigResult r, judgeRendering(rendering, judge));
        if (attempt == 0) {
            const bool retry = worthRetrying(r) && o.retries > 0;
            progress.done(r.id + " " + (r.passed() ? "pass" : retry ? "FAIL (retrying)" : "FAIL"), r.error.empty());
            where[r.id] = run.results.size();
            run.results.push_back(std::move(r));
            return {};
        }
        ConfigResult& before = run.results[where.at(r.id)];
        r.attempts = attempt + 1;
        r.firstFailures = before.firstFailures.empty() ? before.failureLines() : before.firstFailures;
        if (!o.quiet)
            std::fprintf(stderr, "gate: %s %s\n", r.id.c_str(),
                     r.passed() ? ("flaky (failed attempt 1, passed attempt " + std::to_string(r.attempts) + ")").c_str()
                                : ("FAIL (attempt " + std::to_string(r.attempts) + ")").c_str());
        before = std::move(r);
        return {};
    };
    std::vector<render::BackendFailure> failures;
    CAVITY_TRY(render::renderEntries(matrix, entries, ro, sink, &failures));
    for (const auto& f : failures) run.backendErrors.push_back(f.message);
    // A failing configuration is rendered again, up to o.retries times, and
    // one that then passes is flaky: reported as such, never as a plain
    // pass. A configuration that did not run, lacks a baseline, or whose
    // deterministic render failed on images is not retried: another render
    // cannot change that.
    for (attempt = 1; attempt <= o.retries; ++attempt) {
        std::vector<plan::MatrixEntry> again;
        for (const auto& e : entries) {
            const auto at = where.find(configId(e.config));
            if (at == where.end()) continue;
            const ConfigResult& r = run.results[at->second];
            if (worthRetrying(r)) again.push_back(e);
        }
        if (again.empty()) break;
        CAVITY_TRY(render::renderEntries(matrix, again, ro, sink, nullptr));
    }
    run.applyStrict();
    applyExpectations(run, expectations);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

}  // namespace cavity::gate
