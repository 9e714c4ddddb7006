// `cavity gate`, `cavity gate judge` and `cavity gate merge`.
#include "gate/baseline_update.h"
#include "gate_outputs.h"
#include "pipeline/config_id.h"
#include "gate/expectations.h"
#include "core/digest.h"
#include "core/json_file.h"
#include "report/gate_report.h"
#include "staging.h"
#include "images/image_io.h"
#include "gate/judge_folders.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "shard_sources.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include <unistd.h>

namespace cavity::cli {

namespace fs = std::filesystem;

namespace {

const FlagSpec kReportUrlFlag{"--report-url", "URL",
                               "where index.html will be published (a CI artifact): summary.md links it and status.json "
                               "gives it as target_url"};

const std::string kEnforceHelp =
    "fail on a time budget overrun on a software renderer too (llvmpipe, lavapipe: by default reported, never "
    "failed, as the host's load moves those times)";

// An --expectations folder given on the command line must be one; the
// default, <baselines>/expectations, may be absent (no expectations).
Status checkExpectationsFlag(const std::string& dir) {
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec))
        return badInput("--expectations " + dir + ": " + (fs::exists(dir, ec) ? "not a folder" : "no such folder") +
                        " (a folder of expectation files, one per device class)");
    return {};
}

const CommandSpec& gateSpec() {
    static const CommandSpec spec{
        "cavity gate",
        "Runs a matrix of baselines/matrices.json against the baselines and budgets; writes junit.xml, summary.md, "
        "index.html and gate.json under --out. Subcommands: cavity gate judge, cavity gate merge (see their --help).",
        {
            {"--matrix", "NAME", "the matrix of matrices.json (default ci)"},
            {"--baselines", "DIR", kBaselinesHelp},
            {"--out", "DIR", "report folder (default out/gate)"},
            kReportUrlFlag,
            {"--filter", "REGEX", "only the configurations whose id matches (searched)"},
            {"--shard", "I/N", "shard I of N (0 <= I < N); also GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS, TEST_SHARD_INDEX"},
            {"--device", "K", "device index (0..64)"},
            {"--retries", "N", "renders of a failing configuration after the first (0..100; default 2)"},
            {"--expectations", "DIR", "folder of expectation files (default <baselines>/expectations)"},
            {"--validation", "", "enable the Vulkan validation layers and the GL debug output"},
            {"--enforce-cpu-budgets", "", kEnforceHelp},
            {"--strict", "", "fail a configuration that changed in any pixel, within tolerance or not (digests must match)"},
            storeFlag(),
            storeCacheFlag(),
            {"--kernel-source", "NAME=FILE",
             "render with kernels/NAME replaced by FILE's text (a shader edit or a planted defect, no rebuild); "
             "repeatable, each NAME once; every report records FILE and its digest", "Options", true},
            {"--list", "", "print the ids of the selection, one a line, and render nothing"},
            {"--quiet", "", "no progress lines on stderr"},
        },
        "",
        "",
        "\nExit codes: 0 all pass, 1 a regression or an unexpected pass, 2 bad input, 3 a backend could not start, 5 the "
        "image store cannot be reached or lacks a reference, 6 a store object does not match its digest.",
        {
            "cavity gate",
            "cavity gate --matrix ci --filter '/alchemy_fast/' --out out/gate",
            "cavity gate --filter '/alchemy_fast/' --kernel-source ssao_alchemy_fast.glsl=edit.glsl",
        },
    };
    return spec;
}

const CommandSpec& judgeSpec() {
    static const CommandSpec spec{
        "cavity gate judge",
        "Judges render folders written by cavity_render against the baselines (the gate in two steps). Nothing is "
        "written unless every folder is whole.",
        {
            {"--baselines", "DIR", kBaselinesHelp},
            {"--expectations", "DIR", "folder of expectation files (default <baselines>/expectations)"},
            {"--out", "DIR", "report folder (default out/gate)"},
            kReportUrlFlag,
            {"--enforce-cpu-budgets", "", kEnforceHelp},
            {"--strict", "", "fail a configuration that changed in any pixel, within tolerance or not (digests must match)"},
            {"--shards", "I[,J...]/N", "the shards the folders hold, when not all N (default: every shard must be there)"},
            storeFlag(),
            storeCacheFlag(),
            {"--quiet", "", "no progress lines on stderr"},
        },
        "RENDER_DIR...",
        "folders written by cavity_render",
        "",
        {
            "cavity gate judge out/render",
            "cavity gate judge --out out/gate out/render-gl out/render-vk",
            "cavity gate judge --shards 1/4 --out out/gate-1 out/render-1",
        },
    };
    return spec;
}

const CommandSpec& mergeSpec() {
    static const CommandSpec spec{
        "cavity gate merge",
        "Joins the gate.json of shard outputs into one verdict and report, and copies each shard's images under --out "
        "(hard links where it can), so that baselines update and approve read the merged folder as a whole gate's.",
        {{"--out", "DIR", "report folder (default out/gate)"}, kReportUrlFlag},
        "SHARD_DIR...",
        "output folders of cavity gate --shard runs",
        "",
        {
            "cavity gate merge --out out/gate out/gate0 out/gate1",
            "cavity gate merge out/shard-*",
        },
    };
    return spec;
}

// --help prints and ends the command (exit 0); an error ends it (exit 2).
#define CAVITY_PARSE(var, spec, argv)                              \
    auto var##_ = parseFlags(spec, argv);                          \
    if (!var##_) return fail((spec).program, var##_.error());      \
    if (var##_->help) {                                            \
        std::cout << var##_->helpText;                             \
        return 0;                                                  \
    }                                                              \
    const ParsedFlags& var = *var##_;


// The reports the gate writes at its end can replace what --out holds.
Status reportFilesWritable(const std::string& out) {
    return checkOutputFiles("--out", out, {std::begin(gate::kReportFiles), std::end(gate::kReportFiles)});
}

int merge(const std::vector<std::string>& argv) {
    std::vector<std::string> dirs;
    std::string out = "out/gate", reportUrl;
    CAVITY_PARSE(p, mergeSpec(), argv);
    dirs = p.positionals;
    for (const auto& [flag, v] : p.values) (flag == "--out" ? out : reportUrl) = v;
    if (dirs.empty()) return fail("cavity gate merge", badInput("needs one or more shard output folders"));
    // The merged reports written over a shard's would lose that shard.
    for (const auto& d : dirs) {
        std::error_code ec;
        if (fs::equivalent(d, out, ec))
            return fail("cavity gate merge", badInput("--out " + out + ": is " + d + ", a shard merged (give the merge a folder of its own)"));
    }
    gate::GateRun merged;
    std::set<std::pair<std::string, int>> seen;
    std::map<int, std::string> shards;   // index -> its folder
    std::map<std::string, std::string> owner;   // configuration id -> its shard's folder
    for (const auto& d : dirs) {
        auto run = loadGateJson(d);
        if (!run) return fail("cavity gate merge", run.error());
        if (merged.matrix.empty()) {
            merged.matrix = run->matrix;
            merged.filter = run->filter;
            merged.replaced = run->replaced;
            merged.packages = run->packages;
            merged.strict = run->strict;
            merged.shardCount = run->shardCount;
        }
        else if (merged.matrix != run->matrix)
            return fail("cavity gate merge", badInput(d + ": matrix " + run->matrix + " differs from " + merged.matrix));
        else if (measure::packagesJson(merged.packages) != measure::packagesJson(run->packages))
            return fail("cavity gate merge", badInput(d + ": judged kernel packages " + core::jsonText(measure::packagesJson(run->packages)) +
                                                      ", unlike the shards before it (gate every shard with the same --kernels)"));
        else if (merged.filter != run->filter)
            return fail("cavity gate merge", badInput(d + ": --filter '" + run->filter + "', unlike the shards before it ('" +
                                                      merged.filter + "'): gate every shard with one filter"));
        else if (render::replacedJson(merged.replaced) != render::replacedJson(run->replaced))
            return fail("cavity gate merge", badInput(d + ": kernel sources " + core::jsonText(render::replacedJson(run->replaced)) +
                                                      ", unlike the shards before it (gate every shard with the same --kernel-source)"));
        else if (merged.strict != run->strict)
            return fail("cavity gate merge", badInput(d + ": --strict " + (run->strict ? "given" : "not given") +
                                                      ", unlike the shards before it (gate every shard alike)"));
        // The merge is the verdict of the whole matrix: every shard of one
        // split, each once, or a shard missing would pass unseen.
        const std::string shard = std::to_string(run->shardIndex) + "/" + std::to_string(run->shardCount);
        if (run->shardCount != merged.shardCount)
            return fail("cavity gate merge", badInput(d + ": shard " + shard + " is of another split than " +
                                                      std::to_string(merged.shardCount) + " shards"));
        if (const auto [at, fresh] = shards.emplace(run->shardIndex, d); !fresh)
            return fail("cavity gate merge", badInput(d + ": shard " + shard + " is given twice (also " + at->second + ")"));
        merged.seconds = std::max(merged.seconds, run->seconds);
        merged.renderSeconds = std::max(merged.renderSeconds, run->renderSeconds);
        for (auto& e : run->backendErrors) merged.backendErrors.push_back(e);
        // A configuration is in one shard: one in two is a folder copied or
        // mislabelled, whose own shard's results are then missing.
        for (auto& r : run->results) {
            if (const auto [at, fresh] = owner.emplace(r.id, d); !fresh && at->second != d)
                return fail("cavity gate merge", badInput(d + ": " + r.id + " is also in " + at->second +
                                                          " (a configuration belongs to one shard)"));
            if (seen.insert({r.id, r.repetition}).second) merged.results.push_back(std::move(r));
        }
    }
    if (shards.size() != size_t(merged.shardCount)) {
        std::string missing;
        for (int i = 0, n = 0; i < merged.shardCount && n < 8; ++i)
            if (!shards.count(i)) missing += (n++ ? ", " : "") + std::to_string(i);
        return fail("cavity gate merge", badInput("shards of " + std::to_string(merged.shardCount) + ": " +
                                                  std::to_string(merged.shardCount - int(shards.size())) +
                                                  " missing (" + missing + (merged.shardCount - int(shards.size()) > 8 ? ", ..." : "") +
                                                  "); give every shard's folder"));
    }
    merged.shardCount = 1;   // the whole matrix
    if (auto st = checkWritableDir("--out", out); !st) return fail("cavity gate merge", st.error());
    if (auto st = reportFilesWritable(out); !st) return fail("cavity gate merge", st.error());
    merged.out = out;
    if (auto st = gatherShardImages(owner, out, merged); !st) return fail("cavity gate merge", st.error());
    if (auto st = report::writeReports(merged, out, reportUrl); !st) return fail("cavity gate merge", st.error());
    std::cout << report::summaryMarkdown(merged, reportUrl.empty() ? "index.html" : reportUrl);
    return merged.exitCode();
}

// The run's exit code; a store that failed it (5, 6) is also said on
// stderr in one line, as every other failure is, beside the whole report.
int finished(const std::string& program, const gate::GateRun& run) {
    const int code = run.exitCode();
    if (code == 5 || code == 6)
        for (const auto& r : run.results)
            if (r.errorCode == code) {
                std::cerr << program << ": " << r.error << "\n";
                break;
            }
    return code;
}

// The reports and new images go beside the references otherwise: a
// baselines folder is a tree under review, and its images/ holds the
// references themselves.
Status outsideBaselines(const std::string& out, const std::string& baselines) {
    std::error_code ec;
    const fs::path o = fs::weakly_canonical(out, ec), b = fs::weakly_canonical(baselines, ec);
    const auto rel = o.lexically_relative(b);
    if (!rel.empty() && *rel.begin() != "..")
        return badInput("--out " + out + ": is " + (rel == "." ? "" : "inside ") + "the baselines folder " + baselines +
                        " (give a folder of its own, e.g. out/gate)");
    return reportFilesWritable(out);
}

// Nothing is written unless every folder is whole (judge_folders.h).
int judge(const std::vector<std::string>& argv) {
    std::string expectationsDir, reportUrl;
    gate::JudgeOptions o;
    std::string& baselines = o.baselines;
    baselines.clear();
    CAVITY_PARSE(p, judgeSpec(), argv);
    const std::vector<std::string> dirs = p.positionals;
    const std::map<std::string, std::string*> into{{"--out", &o.out}, {"--baselines", &baselines},
                                                   {"--report-url", &reportUrl}, {"--expectations", &expectationsDir},
                                                   {"--store", &o.store.location}, {"--store-cache", &o.store.cache},
                                                   {"--shards", &o.shards}};
    for (const auto& [flag, v] : p.values) *into.at(flag) = v;
    o.quiet = p.has("--quiet");
    o.enforceCpuBudgets = p.has("--enforce-cpu-budgets");
    const bool strict = p.has("--strict");
    if (auto st = checkExpectationsFlag(expectationsDir); !st) return fail("cavity gate judge", st.error());
    const std::string givenBaselines = baselines;
    if (baselines.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail("cavity gate judge", found.error());
        baselines = *found;
    }
    if (auto st = outsideBaselines(o.out, baselines); !st) return fail("cavity gate judge", st.error());
    if (auto st = gate::recoverBaselineUpdate(baselines); !st) return fail("cavity gate judge", st.error());
    auto expectations =
        gate::loadExpectations(expectationsDir.empty() ? (fs::path(baselines) / "expectations").string() : expectationsDir);
    if (!expectations) return fail("cavity gate judge", expectations.error());
    const std::string out = o.out;
    const fs::path staging = stagingDir(out);   // the new images, until the reports are written
    o.out = staging.string();
    auto run = gate::judgeFolders(dirs, o);
    std::error_code ec;
    if (!run) return fs::remove_all(staging, ec), fail("cavity gate judge", run.error());
    run->strict = strict;
    run->applyStrict();
    gate::applyExpectations(*run, *expectations);
    run->baselines = givenBaselines;
    if (auto st = writeGateOutput(*run, staging, out, reportUrl); !st) return fail("cavity gate judge", st.error());
    std::cout << report::summaryMarkdown(*run, reportUrl.empty() ? "index.html" : reportUrl);
    std::cout << "\nreport: " << (fs::path(out) / "index.html").string() << "\n";
    return finished("cavity gate judge", *run);
}

struct GateFlags {
    gate::GateOptions options;
    std::optional<std::string> shard;   // --shard I/N as given
    std::string reportUrl;              // --report-url
    bool list = false;
    std::string helpText;               // --help: print this, run nothing
};

Result<GateFlags> parseGate(const std::vector<std::string>& argv) {
    GateFlags f;
    gate::GateOptions& o = f.options;
    CAVITY_ASSIGN(const ParsedFlags p, parseFlags(gateSpec(), argv));
    if (p.help) {
        f.helpText = p.helpText;
        return f;
    }
    f.list = p.has("--list");
    o.validation = p.has("--validation");
    o.quiet = p.has("--quiet");
    o.enforceCpuBudgets = p.has("--enforce-cpu-budgets");
    o.strict = p.has("--strict");
    o.baselines.clear();
    for (const auto& [flag, v] : p.values) {
        if (flag == "--matrix") o.matrix = v;
        else if (flag == "--out") o.out = v;
        else if (flag == "--report-url") f.reportUrl = v;
        else if (flag == "--baselines") o.baselines = v;
        else if (flag == "--filter") o.filter = v;
        else if (flag == "--shard") f.shard = v;
        else if (flag == "--expectations") o.expectations = v;
        else if (flag == "--store") o.store.location = v;
        else if (flag == "--store-cache") o.store.cache = v;
        else if (flag == "--kernel-source") {
            CAVITY_TRY(addKernelSource(v, o.overrides, o.replaced));
        }
        else if (flag == "--device") {
            CAVITY_ASSIGN(o.device, parseInt(flag, v, 0, 64));
        } else if (flag == "--retries") {
            CAVITY_ASSIGN(o.retries, parseInt(flag, v, 0, 100));
        }
    }
    CAVITY_TRY(checkExpectationsFlag(o.expectations));
    return f;
}

}  // namespace

int gateCommand(const std::vector<std::string>& argv) {
    if (!argv.empty() && argv[0] == "merge") return merge({argv.begin() + 1, argv.end()});
    if (!argv.empty() && argv[0] == "judge") return judge({argv.begin() + 1, argv.end()});
    auto parsed = parseGate(argv);
    if (!parsed) return fail("cavity gate", parsed.error());
    if (!parsed->helpText.empty()) {
        std::cout << parsed->helpText;
        return 0;
    }
    gate::GateOptions& o = parsed->options;
    const bool list = parsed->list;
    const std::string givenBaselines = o.baselines;
    if (o.baselines.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail("cavity gate", found.error());
        o.baselines = *found;
    }
    // --shard, GoogleTest's and Bazel's variables (shard_sources.h).
    auto shard = resolveShard(parsed->shard);
    if (!shard) return fail("cavity gate", shard.error());
    std::tie(o.shardIndex, o.shardCount) = std::pair{shard->index, shard->count};
    if (auto st = touchShardStatusFiles(); !st) return fail("cavity gate", st.error());
    if (const char* hook = std::getenv("CAVITY_TEST_FLAKY")) o.flakyForTest = hook;
    if (list) {
        // The selection, one id a line, nothing rendered: what a shard holds.
        auto m = plan::loadMatrix((fs::path(o.baselines) / "matrices.json").string(), o.matrix);
        if (!m) return fail("cavity gate", m.error());
        auto entries = plan::selectEntries(*m, o.shardIndex, o.shardCount, o.filter);
        if (!entries) return fail("cavity gate", entries.error());
        for (const auto& e : *entries) std::cout << configId(e.config) << "\n";
        return 0;
    }
    if (auto st = outsideBaselines(o.out, o.baselines); !st) return fail("cavity gate", st.error());
    if (auto st = gate::recoverBaselineUpdate(o.baselines); !st) return fail("cavity gate", st.error());
    const std::string out = o.out;
    const fs::path staging = stagingDir(out);   // the new images, until the reports are written
    o.out = staging.string();
    auto run = gate::runGate(o);
    std::error_code ec;
    if (!run) return fs::remove_all(staging, ec), fail("cavity gate", run.error());
    run->baselines = givenBaselines;
    if (auto st = writeGateOutput(*run, staging, out, parsed->reportUrl); !st) return fail("cavity gate", st.error());
    std::cout << report::summaryMarkdown(*run, parsed->reportUrl.empty() ? "index.html" : parsed->reportUrl);
    std::cout << "\nreport: " << (fs::path(out) / "index.html").string() << "\n";
    return finished("cavity gate", *run);
}

}  // namespace cavity::cli
