// `cavity run`: a sweep of configurations on one or both backends, with
// images, results.json and a timing table on stdout.
#include "core/shell_words.h"
#include "run_sweep.h"
#include "staging.h"
#include "run_summary.h"
#include "report/run_page.h"
#include "pipeline/config_id.h"
#include "images/gbuffer_import.h"
#include "core/progress.h"
#include "measure/runner.h"
#include "core/text_table.h"
#include "render/render_manifest.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>


namespace cavity::cli {

namespace {

// Imported G-buffers by size, each read once, before anything runs or is written.
using Captures = std::map<std::pair<int, int>, std::shared_ptr<const GBufferImages>>;

// Without --res, a run with --gbuffer import takes the capture's size.
Status readCaptureSize(Sweep& s, Captures& captures) {
    if (s.gbufferFile.empty() || s.sizeGiven) return {};
    CAVITY_ASSIGN(auto g, importGBuffer(s.gbufferFile));
    const std::pair<int, int> size{g.position.width, g.position.height};
    s.sizes = {size};
    captures[size] = std::make_shared<const GBufferImages>(std::move(g));
    return {};
}

Status attachCaptures(std::vector<RunConfig>& configs, Captures& captures) {
    for (auto& c : configs) {
        if (!c.imported()) continue;
        auto& images = captures[{c.width, c.height}];
        if (!images) {
            CAVITY_ASSIGN(auto g, importGBuffer(c.gbufferFile, c.width, c.height));
            images = std::make_shared<const GBufferImages>(std::move(g));
        }
        c.gbufferImages = images;
    }
    return {};
}

// What runs, in the order it runs: every configuration on each API, those
// --filter selects. --list prints exactly these ids.
Result<std::vector<RunConfig>> planRuns(const Sweep& s, const std::vector<RunConfig>& configs,
                                        const std::vector<gpu::Api>& apis) {
    std::vector<RunConfig> plan;
    for (auto api : apis)
        for (auto c : configs) {
            c.api = api;
            if (s.filter && !std::regex_search(configId(c), *s.filter)) continue;
            plan.push_back(std::move(c));
        }
    if (s.filter && plan.empty())
        return badInput("--filter " + s.filterText + ": matches none of the " + std::to_string(configs.size() * apis.size()) +
                        " configurations of this sweep");
    return plan;
}

std::vector<gpu::Api> sweepApis(const Sweep& s) {
    std::vector<gpu::Api> apis;
    for (const auto& b : s.backends) {
        if (b == "gl" || b == "all") apis.push_back(gpu::Api::OpenGL);
        if (b == "vk" || b == "all") apis.push_back(gpu::Api::Vulkan);
    }
    return apis;
}

// What the runs gave: their records, the errors, and the worst exit code.
struct RunOutcome {
    std::vector<RunRecord> runs;
    std::vector<RunError> errors;
    int worst = 0;
    void failed(const std::string& api, const std::string& what, const Error& e) {
        std::cerr << "cavity run: " << what << e.message << "\n";
        errors.push_back({api, exitCode(e), what + e.message});
        worst = std::max(worst, exitCode(e));
    }
};

// The plan's configurations of one API on its backend, in plan order.
void runOnBackend(gpu::Backend& gpu, gpu::Api api, const std::vector<RunConfig>& plan, const RunOptions& options,
                  Progress& progress, RunOutcome& out) {
    for (const auto& c : plan) {
        if (c.api != api) continue;
        progress.start(configId(c));
        auto r = runConfig(gpu, c, options);
        if (!r) {
            progress.interrupt();
            out.failed(gpu::apiName(api), configId(c) + ": ", r.error());
            continue;
        }
        if (!r->debugMessages.empty() || !r->nonFinite.empty()) progress.interrupt();
        for (const auto& m : r->debugMessages) std::cerr << "cavity run: " << gpu::apiName(api) << " debug: " << m << "\n";
        // Exit 1: the run finished, but a pass wrote NaN or infinity
        // (README, Exit codes); its images and results are still written.
        for (const auto& n : r->nonFinite) {
            std::cerr << "cavity run: " << configId(c) << ": " << n.message() << "\n";
            out.worst = std::max(out.worst, int(ErrorCode::CheckFailed));
        }
        out.runs.push_back(std::move(*r));
    }
}

// The images are written under a staging folder in --out (staging.h), and
// move to their places only once every configuration has run.
Status runFilesMovedIn(const std::filesystem::path& staging, const std::string& out, const RunOutcome& outcome) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (const auto& r : outcome.runs) {
        const std::string id = configId(r.config);
        const fs::path from = staging / id, to = fs::path(out) / id;
        if (!fs::exists(from, ec)) continue;
        ec = replaceFolder(from, to);
        if (ec) return badInput("--out " + out + ": cannot move " + id + " in: " + ec.message());
    }
    fs::remove_all(staging, ec);
    return {};
}

RunOutcome runPlan(const Sweep& s, const std::vector<gpu::Api>& apis, const std::vector<RunConfig>& plan,
                   const std::filesystem::path& staging) {
    RunOutcome out;
    RunOptions options = s.options;
    options.outDir = staging.string();
    Progress progress(plan.size(), s.quiet);
    for (auto api : apis) {
        auto backend = gpu::createBackend(api, s.backend);
        progress.interrupt();
        if (!backend) {
            out.failed(gpu::apiName(api), "", backend.error());
            continue;
        }
        // Which device ran, unless --quiet (then stderr is errors alone).
        if (!s.quiet)
            std::cerr << "cavity run: " << gpu::apiName(api) << ": " << (*backend)->info().deviceName << " ("
                      << (*backend)->info().driver << ")\n";
        runOnBackend(**backend, api, plan, options, progress, out);
    }
    progress.interrupt();
    return out;
}

// results.json, table.txt and index.html, then the summary that names them.
Status writeResults(const Sweep& s, const RunOutcome& out, const std::vector<std::string>& argv) {
    std::vector<std::string> args;
    const auto packages = measure::packagesLoaded();
    for (const auto& p : packages) args.insert(args.end(), {"--kernels", p.folder});
    args.insert(args.end(), argv.begin(), argv.end());
    const std::string command = core::commandLine("cavity run", args);
    std::error_code ec;
    std::filesystem::create_directories(s.out, ec);
    const std::filesystem::path dir(s.out);
    const std::string results = (dir / "results.json").string();
    auto doc = resultsDocument(out.runs, out.errors, command);
    // What was measured in place of the kernels' own files (--kernel-source):
    // a result of an edited kernel is never read as the kernel's.
    if (!s.replaced.empty()) {
        doc["kernel_sources"] = nlohmann::json::array();
        for (const auto& r : s.replaced)
            doc["kernel_sources"].push_back({{"name", r.name}, {"file", r.file}, {"digest", r.digest}});
    }
    if (!packages.empty()) doc["kernel_packages"] = measure::packagesJson(packages);
    const std::string table = (dir / "table.txt").string(), page = (dir / "index.html").string();
    if (out.runs.empty()) {
        // The folder's record is this run's: an earlier run's table and page
        // left beside a results.json of none would be read as this one's.
        std::filesystem::remove(table, ec);
        std::filesystem::remove(page, ec);
        CAVITY_TRY(writeJson(results, doc));
        std::printf("wrote %s (no configuration ran; its errors are in it)\n", results.c_str());
        return {};
    }
    const std::string tableText = runTable(out.runs);
    CAVITY_TRY(writeFileAtomically(table, tableText));
    CAVITY_TRY(report::writeRunPage(s.out, out.runs, command));
    CAVITY_TRY(writeJson(results, doc));   // last: what readers of the folder take as its record
    if (s.table) std::printf("\n%s", tableText.c_str());
    std::printf("%s", runSummary(out.runs, {"wrote " + results + " and " + table + " (every pass, its clock, the notes)",
                                            "open " + page})
                          .c_str());
    return {};
}

}  // namespace

int runCommand(const std::vector<std::string>& argv) {
    auto fail = [](const Error& e) { return cli::fail("cavity run", e); };
    auto parsed = parseSweep(argv);
    if (!parsed) return fail(parsed.error());
    Sweep& s = *parsed;
    if (!s.helpText.empty()) {
        std::cout << s.helpText;
        return 0;
    }
    Captures captures;
    if (auto st = readCaptureSize(s, captures); !st) return fail(st.error());
    auto configs = expandSweep(s);
    if (!configs) return fail(configs.error());
    if (auto st = attachCaptures(*configs, captures); !st) return fail(st.error());
    const auto apis = sweepApis(s);
    auto plan = planRuns(s, *configs, apis);
    if (!plan) return fail(plan.error());
    if (auto st = pipeline::checkSourcesUsed(s.replaced, *plan); !st) return fail(st.error());
    if (s.list) {
        for (const auto& c : *plan) std::cout << configId(c) << "\n";
        return 0;
    }
    if (auto o = gpu::withEnvironment(s.backend); !o) return fail(o.error());
    if (auto st = checkWritableDir("--out", s.out); !st) return fail(st.error());
    if (auto st = checkOutputFiles("--out", s.out, {"results.json", "table.txt", "index.html"}); !st) return fail(st.error());
    const auto staging = stagingDir(s.out);
    const RunOutcome out = runPlan(s, apis, *plan, staging);
    // --max-time bounds a run whatever --frames asks: say where it cut one short.
    for (const auto& r : out.runs)
        if (r.timing.stop == "time" && r.timing.frame.ms.size() < size_t(r.timingOptions.frames))
            std::cerr << "cavity run: " << configId(r.config) << ": --max-time stopped measuring after "
                      << r.timing.frame.ms.size() << " of the " << r.timingOptions.frames << " frames --frames asked for\n";
    if (out.runs.empty() && out.errors.empty()) {
        std::error_code ec;
        std::filesystem::remove_all(staging, ec);
        return out.worst;
    }
    if (auto st = runFilesMovedIn(staging, s.out, out); !st) return fail(st.error());
    if (auto st = writeResults(s, out, argv); !st) return fail(st.error());
    return out.worst;
}

}  // namespace cavity::cli
