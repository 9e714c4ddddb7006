// The pull-request gate: a declared matrix of configurations, each output
// image compared with its stored baseline and each pass's median time with
// its budget. Verdicts go to gate.json (read by `gate merge` and
// `baselines update`), junit.xml, summary.md and index.html (gate_report.h).
// Two halves: rendering (harness/render/rendering.h, no OpenImageIO: cavity_render
// runs it on the GPU machine) and judging (gate_judge.h); runGate does both
// in one process, judge_folders.h judges what cavity_render left.
#pragma once

#include "gate/namespace.h"
#include "gate/baselines.h"
#include "images/metrics.h"
#include "pipeline/pipeline.h"
#include "render/render_manifest.h"
#include "store/store.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cavity::gate {

struct ImageCheck {
    std::string image;                 // "ao", "ao_blur", "color"
    std::string digest;                // digest.h imageDigest() of the new image
    // What decided it: "digest" (an approved positive of this device class:
    // a pass, no metric computed), "negative" (an approved known-bad digest:
    // a failure) or "tolerance" (the metrics against the stored reference).
    std::string route = "tolerance";
    std::string approval;              // who approved it (the digest, or the reference judged against), when, on what, why
    // tolerance: the reference judged against: "default" (the stored
    // baseline, with the manifest's device overrides) or "<class> <api>/<stage>"
    // (the nearest approved image of the device's own class, from the store).
    std::string reference;
    std::string referenceDigest;       // the approved image judged against, when of the device's class
    std::string baseline;              // path of the baseline file (relative to the repo root or absolute)
    std::string newPng, newExact;      // written new image: PNG to look at, and the exact file (.exr / .png)
    std::string baselinePng, diffPng;  // for the report
    std::optional<metrics::Report> metrics;
    Tolerance tolerance;
    std::vector<std::string> failures; // one line each: "rmse 0.0123 > 0.005"
    bool passed() const { return failures.empty(); }
    // Judged by its metrics (no approved digest decided it), and some pixel
    // differs from the reference: a change the tolerance allowed. It passes,
    // and is reported as changed, never as unchanged: the CPU renderers are
    // deterministic, so an image of an unchanged build is the reference's.
    bool changed() const;
};

struct TimingCheck {
    std::string pass;
    double medianMs = 0;
    double lowMs = NAN, highMs = NAN;   // the median's 95% interval over the frames; NaN: too few
    std::optional<double> budgetMs;
    std::string clock;
    // Measured on a software renderer (llvmpipe, lavapipe): the time is the
    // host CPU's, which swings with whatever else the machine runs, so an
    // overrun is reported and never fails the gate (unless
    // GateOptions::enforceCpuBudgets).
    bool advisory = false;
    bool withinBudget() const { return !budgetMs || medianMs <= *budgetMs; }
    bool passed() const { return advisory || withinBudget(); }
};

struct ConfigResult {
    std::string id, key, device;
    std::string driver;                // the device's driver string, for approvals
    int repetition = 0;                // cavity_render --repeat: every repetition is judged
    RunConfig config;
    std::vector<ImageCheck> images;
    std::vector<TimingCheck> timings;
    bool deterministic = true;
    std::string error;                 // the configuration could not run (its message)
    int errorCode = 0;
    // Retries (GateOptions::retries): how many times it was rendered and
    // judged, and what the first failing attempt said when a later one
    // passed. The checks above are the last attempt's.
    int attempts = 1;
    std::vector<std::string> firstFailures;
    // Listed in the device's expectations file (expectations.h): "fail" or
    // "flake", and "FILE:LINE: reason".
    std::string expected, expectedWhy;
    bool imagesPassed() const;
    bool timingPassed() const;
    bool passed() const { return error.empty() && imagesPassed() && timingPassed(); }
    // Some image of it changed within its tolerance (ImageCheck::changed).
    bool changed() const;
    // pass, changed (passed with an image that changed within tolerance),
    // fail, error, flaky (failed, then passed on a retry),
    // expected-fail, known-flake (listed as a flake and failed every
    // attempt) or unexpected-pass (listed as an expected failure, passed).
    std::string verdict() const;
    // Whether the verdict fails the gate: fail, error and unexpected-pass.
    bool fatal() const;
    // Every failure line of the checks above, for the report of a retry.
    std::vector<std::string> failureLines() const;
    // The id, and "(repetition K)" after it for a later repetition.
    std::string label() const;
};

struct GateOptions {
    std::string matrix = "ci";
    std::string baselines = "baselines";   // folder with matrices.json, manifest.json, budgets.json, images/
    std::string out = "out/gate";
    int shardIndex = 0, shardCount = 1;
    int device = 0;
    bool validation = false;
    bool quiet = false;                    // no progress lines on stderr
    std::string filter;                    // regex on configuration ids; empty: all
    int retries = 2;                       // renders of a failing configuration after the first
    std::string expectations;              // folder of expectation files; empty: <baselines>/expectations
    bool enforceCpuBudgets = false;        // a software renderer's budget overrun fails too (TimingCheck::advisory)
    bool strict = false;                   // GateRun::strict
    cavity::store::StoreOptions store;             // --store, --store-cache: where class references are
    SourceOverrides overrides;             // --kernel-source: kernels/ files replaced
    std::vector<ReplacedSource> replaced;  // ... and where each came from, for the reports
    // Test hook (CAVITY_TEST_FLAKY): configurations whose id this regex
    // finds have their first attempt's AO perturbed, so they fail once and
    // pass on a retry. Empty: none.
    std::string flakyForTest;
};

struct GateRun {
    std::string matrix;
    std::string filter;   // the selection's --filter ("" all): shards merge only with one filter
    int shardIndex = 0, shardCount = 1;
    std::vector<ConfigResult> results;
    std::vector<std::string> backendErrors;   // backends that could not start
    std::vector<ReplacedSource> replaced;     // kernel sources replaced (--kernel-source)
    std::vector<measure::PackageUsed> packages;   // packages from disk whose kernels were judged
    double seconds = 0;           // the whole gate: rendering and judging
    double renderSeconds = 0;     // of which rendering in cavity_render (gate judge); 0: rendered in this process
    // --strict: a configuration that changed (any pixel, within tolerance
    // or not) fails the run, as Mesa's trace checksums do.
    bool strict = false;
    // The folder the reports are written to (not in gate.json): the accept
    // commands the reports print name it. "" prints a placeholder.
    std::string out;
    // The --baselines folder given (not in gate.json), which the accept
    // commands name too; "" when the default was found, which they find.
    std::string baselines;
    // 0 all pass (flaky, expected-fail and known-flake included), 1 a
    // regression or an unexpected pass, 2 bad input (a baseline missing or
    // unreadable), 3 a backend could not start.
    int exitCode() const;
    // Under --strict, every image that changed within its tolerance gets a
    // failure line, so that each report (summary.md, junit.xml, gate.json,
    // status.json, the HTML page) fails it as the exit code does.
    void applyStrict();
    // Configurations per verdict().
    std::map<std::string, int> counts() const;
};

// Every verdict() there is, in the order the reports count them.
inline constexpr const char* kVerdicts[] = {"fail", "error", "unexpected-pass", "flaky", "known-flake", "expected-fail",
                                           "changed", "pass"};

// Validates every input file first (exit 2 before any GPU work), then
// renders and judges each configuration in turn.
Result<GateRun> runGate(const GateOptions& o);

// The reports a gate output folder holds; gate.json is the one the other
// commands read, so it is written last (report/gate_report.h).
inline constexpr const char* kReportFiles[] = {"index.html", "summary.md", "junit.xml", "status.json", "gate.json"};
// Removes an earlier run's reports from `out` before its images are
// overwritten: a run killed after that point leaves images and no verdict,
// never an old verdict over new images.
void dropStaleReports(const std::string& out);

nlohmann::json toJson(const GateRun& run);
// The pieces of gate.json that render folders also carry (RemoteCheck).
nlohmann::json toleranceJson(const Tolerance& t);
nlohmann::json metricsJson(const metrics::Report& m);
Result<metrics::Report> metricsFromJson(const nlohmann::json& j, const std::string& where);
Result<GateRun> fromJson(const nlohmann::json& j, const std::string& path);

}  // namespace cavity::gate
