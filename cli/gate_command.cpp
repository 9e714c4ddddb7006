// `cavity gate`, `cavity gate judge`, `cavity gate merge` and `cavity baselines update`.
#include "gate/baseline_update.h"
#include "gate_outputs.h"
#include "pipeline/config_id.h"
#include "gate/expectations.h"
#include "core/digest.h"
#include "core/json_file.h"
#include "report/gate_report.h"
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

const std::string kBaselinesHelp =
    "folder with matrices.json, manifest.json, budgets.json, images/ (default: baselines/ of the checkout found "
    "from the working directory up, else of the source tree this binary was built from)";

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
        "Joins the gate.json of shard outputs into one verdict and report.",
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

const CommandSpec& updateSpec() {
    static const CommandSpec spec{
        "cavity baselines update",
        "Accepts a gate run's new images as baselines: without --filter the configurations that failed, with it "
        "every image of the configurations it selects. All or nothing.",
        {
            {"--from", "DIR", "a gate output folder with gate.json (default out/gate)"},
            {"--filter", "REGEX", "take the configurations whose id matches"},
            {"--baselines", "DIR", kBaselinesHelp},
            {"--with-kernel-source", "", "the run replaced kernel sources (--kernel-source): also copy each file over its "
                                         "kernels/NAME, so that the tree renders what the baselines show"},
        },
        "",
        "",
        "",
        {
            "cavity baselines update --from out/gate",
            "cavity baselines update --from out/gate --filter '^corner/alchemy/'",
            "cavity baselines update --from out/gate --with-kernel-source",
        },
    };
    return spec;
}

// What to do when configurations failed on time budgets alone: images are
// not what a baseline update changes.
std::string budgetOnlyHint(const gate::GateRun& run, bool filtered, const std::string& from) {
    int budgetOnly = 0;
    std::string device;
    for (const auto& r : run.results)
        if (r.error.empty() && r.imagesPassed() && !r.timingPassed()) {
            ++budgetOnly;
            device = r.device;
        }
    if (budgetOnly == 0 || filtered) return "";
    return std::to_string(budgetOnly) + " configurations failed on time budgets only (every image passed): budgets are " +
           "not images; update them with `python3 scripts/update_budgets.py " + (fs::path(from) / "gate.json").string() +
           " --pattern '" + device + "'` (docs/gate.md, \"Time budgets\")";
}

// The files a run rendered in place of kernels/ (--kernel-source), each
// read and checked to be what was rendered, with where it goes in the tree
// beside `root`. A run with replaced sources is refused without
// --with-kernel-source: its images are not what kernels/ renders, and
// accepting them alone would leave tree and baselines disagreeing.
Result<std::map<fs::path, std::pair<std::string, std::string>>> kernelSourceCopies(const gate::GateRun& run,
                                                                                  const std::string& root,
                                                                                  const std::string& from, bool take) {
    std::map<fs::path, std::pair<std::string, std::string>> out;   // target -> (file, text)
    if (run.replaced.empty()) return out;
    std::string names;
    for (const auto& r : run.replaced) names += (names.empty() ? "kernels/" : ", kernels/") + r.name;
    if (!take)
        return badInput("--from " + from + ": rendered with " + names + " replaced (--kernel-source): its images are "
                        "not what kernels/ renders; pass --with-kernel-source to copy the edits into kernels/ with the "
                        "baselines, or copy them yourself and run the gate again");
    std::error_code ec;
    const fs::path tree = fs::absolute(root, ec).lexically_normal().parent_path() / "kernels";
    for (const auto& r : run.replaced) {
        const fs::path target = tree / r.name;
        if (!fs::is_regular_file(target, ec))
            return badInput("--with-kernel-source: kernels/" + r.name + " is not a file of " + tree.string() +
                            " (a kernel package outside the tree is updated where it lives)");
        std::ifstream in(r.file, std::ios::binary);
        if (!in) return badInput("--with-kernel-source: " + r.file + " (for kernels/" + r.name + "): cannot be read");
        std::string text((std::istreambuf_iterator<char>(in)), {});
        if (const std::string digest = core::digestText(core::fnv1a64(text.data(), text.size())); digest != r.digest)
            return badInput("--with-kernel-source: " + r.file + " changed since the run (digest " + digest +
                            ", the run rendered " + r.digest + "): run the gate again");
        out[target] = {r.file, std::move(text)};
    }
    return out;
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


int merge(const std::vector<std::string>& argv) {
    std::vector<std::string> dirs;
    std::string out = "out/gate", reportUrl;
    CAVITY_PARSE(p, mergeSpec(), argv);
    dirs = p.positionals;
    for (const auto& [flag, v] : p.values) (flag == "--out" ? out : reportUrl) = v;
    if (dirs.empty()) return fail("cavity gate merge", badInput("needs one or more shard output folders"));
    gate::GateRun merged;
    std::set<std::pair<std::string, int>> seen;
    for (const auto& d : dirs) {
        auto run = loadGateJson(d);
        if (!run) return fail("cavity gate merge", run.error());
        if (merged.matrix.empty()) {
            merged.matrix = run->matrix;
            merged.replaced = run->replaced;
        }
        else if (merged.matrix != run->matrix)
            return fail("cavity gate merge", badInput(d + ": matrix " + run->matrix + " differs from " + merged.matrix));
        merged.seconds = std::max(merged.seconds, run->seconds);
        merged.renderSeconds = std::max(merged.renderSeconds, run->renderSeconds);
        for (auto& e : run->backendErrors) merged.backendErrors.push_back(e);
        for (auto& r : run->results)
            if (seen.insert({r.id, r.repetition}).second) merged.results.push_back(std::move(r));
    }
    if (auto st = checkWritableDir("--out", out); !st) return fail("cavity gate merge", st.error());
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
    if (baselines.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail("cavity gate judge", found.error());
        baselines = *found;
    }
    if (auto st = gate::recoverBaselineUpdate(baselines); !st) return fail("cavity gate judge", st.error());
    auto expectations =
        gate::loadExpectations(expectationsDir.empty() ? (fs::path(baselines) / "expectations").string() : expectationsDir);
    if (!expectations) return fail("cavity gate judge", expectations.error());
    auto run = gate::judgeFolders(dirs, o);
    if (!run) return fail("cavity gate judge", run.error());
    run->strict = strict;
    gate::applyExpectations(*run, *expectations);
    if (auto st = report::writeReports(*run, o.out, reportUrl); !st) return fail("cavity gate judge", st.error());
    std::cout << report::summaryMarkdown(*run, reportUrl.empty() ? "index.html" : reportUrl);
    std::cout << "\nreport: " << (fs::path(o.out) / "index.html").string() << "\n";
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
    if (auto st = gate::recoverBaselineUpdate(o.baselines); !st) return fail("cavity gate", st.error());
    auto run = gate::runGate(o);
    if (!run) return fail("cavity gate", run.error());
    if (auto st = report::writeReports(*run, o.out, parsed->reportUrl); !st) return fail("cavity gate", st.error());
    std::cout << report::summaryMarkdown(*run, parsed->reportUrl.empty() ? "index.html" : parsed->reportUrl);
    std::cout << "\nreport: " << (fs::path(o.out) / "index.html").string() << "\n";
    return finished("cavity gate", *run);
}

int baselinesCommand(const std::vector<std::string>& argv) {
    if (!argv.empty() && (argv[0] == "--help" || argv[0] == "-h")) {
        std::cout << "usage: cavity baselines update|approve [flags]   (see cavity baselines update --help, "
                     "cavity baselines approve --help)\n";
        return 0;
    }
    if (!argv.empty() && argv[0] == "approve") return approveCommand({argv.begin() + 1, argv.end()});
    if (argv.empty() || argv[0] != "update")
        return fail("cavity baselines", badInput("'" + (argv.empty() ? std::string() : argv[0]) +
                                                 "': usage: cavity baselines update|approve [flags]"));
    std::string from = "out/gate", filterText, root;
    CAVITY_PARSE(p, updateSpec(), std::vector<std::string>(argv.begin() + 1, argv.end()));
    for (const auto& [flag, v] : p.values) {
        if (flag == "--from") from = v;
        else if (flag == "--filter") filterText = v;
        else if (flag == "--baselines") root = v;
    }
    if (root.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail("cavity baselines update", found.error());
        root = *found;
    }
    std::optional<std::regex> filter;
    if (!filterText.empty()) {
        auto r = parseFilter("--filter", filterText);
        if (!r) return fail("cavity baselines update", r.error());
        filter = std::move(*r);
    }
    if (auto st = gate::recoverBaselineUpdate(root); !st) return fail("cavity baselines update", st.error());
    auto run = loadGateJson(from);
    if (!run) return fail("cavity baselines update", run.error());
    auto sources = kernelSourceCopies(*run, root, from, p.has("--with-kernel-source"));
    if (!sources) return fail("cavity baselines update", sources.error());
    // One baseline key is shared by every API and stage: take the first
    // selected configuration of each key.
    std::set<std::string> done;
    std::vector<gate::BaselineWrite> writes;
    std::vector<std::string> said;
    for (const auto& r : run->results) {
        // Without a filter, what failed the gate: an expected failure or a
        // known flake is not accepted as the new baseline by default.
        const bool selected = filter ? std::regex_search(r.id, *filter) : r.verdict() == "fail";
        if (!selected || !r.error.empty() || done.count(r.key)) continue;
        done.insert(r.key);
        for (const auto& i : r.images) {
            // A selected configuration rewrites the images that failed (all of
            // them when chosen by --filter): passing ones keep their bytes.
            if (!filter && i.passed()) continue;
            const fs::path target = fs::path("images") / r.key / fs::path(i.baseline).filename();
            writes.push_back({i.newExact, target});
            std::ostringstream line;
            line << "updated " << (fs::path(root) / target).string() << "  (from " << r.id;
            if (i.metrics)
                line << ": max abs " << i.metrics->maxAbs << ", RMSE " << i.metrics->rmse << ", SSIM " << i.metrics->ssim;
            else
                line << ": new baseline";
            said.push_back(line.str() + ")");
        }
    }
    // All or nothing (harness/gate/baseline_update.h).
    if (auto st = gate::applyBaselineUpdate(root, writes); !st) return fail("cavity baselines update", st.error());
    for (const auto& line : said) std::cout << line << "\n";
    for (const auto& [target, copy] : *sources) {
        if (auto st = writeFileAtomically(target.string(), copy.second); !st) return fail("cavity baselines update", st.error());
        std::cout << "copied " << copy.first << " over " << target.string() << "\n";
    }
    if (!sources->empty())
        std::cout << "kernels/ now holds the edits the baselines show; rebuild cavity (built-in kernels are compiled in) "
                     "and commit both\n";
    const size_t changed = writes.size();
    std::cout << changed << " baseline files updated\n";
    if (const std::string hint = budgetOnlyHint(*run, filter.has_value(), from); !hint.empty()) std::cout << hint << "\n";
    return 0;
}

}  // namespace cavity::cli
