// `cavity quality`: each AO kernel's error against the ray-traced ground
// truth, as a table on stdout and quality.json.
#include "values.h"
#include "quality_command.h"
#include "quality_page.h"
#include "quality_report.h"
#include "quality_recommend.h"
#include "core/json_file.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "core/progress.h"
#include "measure/quality.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "core/text_table.h"
#include "plan/axes.h"
#include "plan/sweep.h"
#include "package/package.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <optional>
#include <map>
#include <set>
#include <regex>
#include <tuple>

namespace cavity::flags {

namespace {

CommandSpec qualitySpec(const std::string& program) {
    CommandSpec c;
    c.program = program;
    c.description = "Mean absolute error of each AO kernel (raw AO unless --blur) against the ray-traced ground truth.";
    c.flags = {
        {"--backend", "gl|vk", "the backend (default vk)"},
        {"--scene", "S[,S..]", "scenes (default corner,slats)"},
        {"--kernel", "K[,K..]", "AO kernels (default every kernel of role ao; see cavity run --help)"},
        {"--samples", "N[,N..]", "sample counts, each " + kernels::allowedValues(*kernels::findParam("samples")) + " (default 16,64)"},
        {"--res", "WxH", "image size (default 160x90)"},
        {"--rays", "N", "the ground truth's rays per pixel, " + kernels::allowedValues(*kernels::findParam("rays")) + " (default 1024)"},
        {"--resolution", "full|half", "AO at full or half resolution (default full)"},
        {"--reach", "shared|seed", "shared (default): every kernel and the truth at --radius, so that errors "
                                   "compare; seed: each kernel at its own default reach, the truth at 0.5"},
        {"--radius", "R", "the shared reach (default 0.5)"},
        {"--cost", "FILE", "a benchmark of the same kernels (cavity_bench JSON or results.json): adds each "
                           "kernel's AO pipeline time, the screen-space Pareto front and --budget-ms"},
        {"--budget-ms", "MS", "with --cost: the most accurate screen-space kernel whose pipeline fits in MS"},
        {"--blur", "R", "compare the AO after the pipeline's blur of radius R, " + kernels::allowedValues(*kernels::findParam("blur")) + " (default 0, the raw AO)"},
        {"--exact", "0|1", "the fast kernels' arithmetic: 0 the GPU's own, 1 the CPU reference's bit for bit "
                           "(docs/kernels.md, \"The precision contract\"); set on the kernels that declare it "
                           "(default 0)"},
        {"--interleave", "K", "the fast kernels' AO pass as K x K interleaved layers, " +
                                  kernels::allowedValues(*kernels::findParam("interleave")) +
                                  "; set on the kernels that declare it (default 1)"},
        {"--kernel-source", "NAME=FILE", "measure with kernels/NAME replaced by FILE's text (an edited kernel's "
                                          "accuracy); repeatable", "Options", true},
        {"--device", "K", "device index (0..64)"},
        {"--out", "DIR", "also write DIR/quality.json and DIR/quality.html (each kernel's AO and signed error map "
                         "beside the truth)"},
        {"--filter", "REGEX", "only the configurations whose id matches (searched; ids as --list prints them)"},
        {"--list", "", "print the configuration ids this would measure, one a line, and measure nothing"},
        {"--quiet", "", "no progress lines on stderr"},
    };
    // Every other kernel parameter (a built-in's --steps, a loaded package's
    // own), one value each, set on the kernels that declare it: a row is
    // measured at one setting.
    std::set<std::string> dedicated;
    for (const auto& f : c.flags) dedicated.insert(f.name.substr(2));
    std::map<std::string, std::string> owner;   // a package's own parameter -> the package
    for (const auto& p : kernels::packages())
        for (const auto& name : p.builtIn ? std::vector<std::string>{} : p.addedParams) owner.emplace(name, p.name);
    for (const auto& d : kernels::paramDecls()) {
        if (dedicated.count(d.name) || d.name == "scene" || d.name == "blur") continue;
        const auto o = owner.find(d.name);
        c.flags.push_back({"--" + d.name, "V",
                           (o != owner.end() ? "a parameter of " + o->second + "'s package, " : std::string()) +
                               kernels::allowedValues(d) + "; one value, set on the kernels that declare it", "Kernel parameters"});
    }
    c.examples = {
        program + " --kernel alchemy_fast,hemisphere_fast --samples 16 --reach seed",
        program + " --cost bench.json --budget-ms 0.2",
        program + " --scene slats --res 640x360 --blur 4 --out out/quality",
    };
    return c;
}

// What `cavity quality` was asked for.
struct QualityRequest {
    QualityOptions options;
    gpu::Api api = gpu::Api::Vulkan;
    gpu::BackendOptions backend;
    std::string out;
    std::optional<std::regex> filter;
    bool reachGiven = false, radiusGiven = false;
    std::string cost;                  // --cost
    std::optional<double> budgetMs;    // --budget-ms
    std::vector<pipeline::ReplacedSource> replaced;   // --kernel-source
};

// A kernel parameter's value from its flag, checked by its declaration.
Result<double> paramFlag(const std::string& name, const std::string& v) {
    return kernels::parseValue(*kernels::findParam(name), v);
}

// --scene, --kernel, --samples: the configurations' axes, each item checked.
Status axisFlag(QualityRequest& q, const std::string& flag, const std::string& v) {
    CAVITY_ASSIGN(const auto items, splitList(flag, v));
    if (flag == "--scene") {
        for (const auto& s : items) {
            RunConfig probe;
            CAVITY_TRY(setParam(probe, "scene", s));
        }
        q.options.scenes = items;
    } else if (flag == "--kernel") {
        for (const auto& k : items) {
            const auto* d = kernels::find(k);
            if (!d || d->role != kernels::Role::Ao) return badInput("--kernel " + k + ": not an AO kernel (see cavity run --help)");
        }
        q.options.kernels = items;
    } else {
        q.options.samples.clear();
        for (const auto& item : items) {
            CAVITY_ASSIGN(const double n, paramFlag("samples", item));
            q.options.samples.push_back(kernels::asInt(n));
        }
    }
    return {};
}

Status qualityFlag(QualityRequest& q, const std::string& flag, const std::string& v) {
    auto& o = q.options;
    if (flag == "--scene" || flag == "--kernel" || flag == "--samples") return axisFlag(q, flag, v);
    if (flag == "--reach") {
        if (v != "seed" && v != "shared") return badInput("--reach " + v + ": must be seed or shared");
        o.sharedReach = v == "shared";
        q.reachGiven = true;
    } else if (flag == "--radius") {
        CAVITY_ASSIGN(o.radius, paramFlag("radius", v));
        q.radiusGiven = true;
    } else if (flag == "--cost") {
        q.cost = v;
    } else if (flag == "--budget-ms") {
        CAVITY_ASSIGN(q.budgetMs, parseNumber(flag, v, [](double x) { return x > 0; }, "a time in ms > 0"));
    } else if (flag == "--backend") {
        if (v != "gl" && v != "vk") return badInput("--backend " + v + ": must be gl or vk");
        q.api = v == "gl" ? gpu::Api::OpenGL : gpu::Api::Vulkan;
    } else if (flag == "--res") {
        CAVITY_ASSIGN(std::tie(o.width, o.height), parseResolution("--res", v));
    } else if (flag == "--blur" || flag == "--rays") {
        CAVITY_ASSIGN(const double n, paramFlag(flag.substr(2), v));
        (flag == "--blur" ? o.blur : o.rays) = kernels::asInt(n);
    } else if (flag == "--resolution") {
        if (v != "full" && v != "half") return badInput("--resolution " + v + ": must be full or half");
        o.half = v == "half";
    } else if (flag == "--exact" || flag == "--interleave") {
        CAVITY_ASSIGN(o.switches[flag.substr(2)], paramFlag(flag.substr(2), v));
    } else if (flag == "--kernel-source") {
        CAVITY_TRY(addKernelSource(v, o.overrides, q.replaced));
    } else if (flag == "--device") {
        CAVITY_ASSIGN(q.backend.deviceIndex, parseInt("--device", v, 0, 64));
    } else if (flag == "--out") {
        q.out = v;
    } else if (flag == "--filter") {
        CAVITY_ASSIGN(q.filter, parseFilter(flag, v));
    } else if (kernels::findParam(flag.substr(2))) {   // any other kernel parameter (qualitySpec)
        if (v.find(',') != std::string::npos)
            return badInput(flag + " '" + v + "': one value (quality measures each kernel at one setting of it; "
                                   "run it once a value)");
        CAVITY_ASSIGN(o.switches[flag.substr(2)], paramFlag(flag.substr(2), v));
    }
    return {};
}

Result<QualityRequest> parseQuality(const ParsedFlags& parsed) {
    QualityRequest q;
    for (const auto& [flag, value] : parsed.values) CAVITY_TRY(qualityFlag(q, flag, value));
    if (q.radiusGiven && q.reachGiven && !q.options.sharedReach)
        return badInput("--radius " + std::to_string(q.options.radius) + ": only with --reach shared");
    // Shared by default: each kernel at its own reach measures a different
    // quantity (sdf_multiscale read 0.5655 that way, an artifact).
    if (!q.reachGiven) q.options.sharedReach = true;
    if (q.budgetMs && q.cost.empty()) return badInput("--budget-ms: needs --cost FILE (the kernels' measured times)");
    return q;
}

// One measureQuality call and the configuration ids it measures: one scene
// with every kernel (its ground truth rendered once), or with --filter one
// kernel and the sample counts selected.
struct QualityStep {
    QualityOptions options;
    std::vector<std::string> ids;
};

// The configurations measured, as ids: what measureQuality renders for each
// (scene, kernel, samples), the raw AO with the bilateral off.
Result<std::vector<QualityStep>> planQuality(const QualityRequest& q) {
    const auto& o = q.options;
    plan::Axes axes;
    axes.scenes = o.scenes;
    axes.kernels = o.kernels.empty() ? plan::aoKernels() : o.kernels;
    axes.params = {{"samples", std::vector<double>(o.samples.begin(), o.samples.end())}};
    RunConfig base;
    base.api = q.api;
    std::tie(base.width, base.height) = std::pair{o.width, o.height};
    base.params["blur"] = o.blur;
    base.stage = o.stage;
    std::vector<QualityStep> steps;
    std::vector<RunConfig> measured;
    CAVITY_TRY(plan::forEachConfig(axes, base, [&](RunConfig c) -> Status {
        // A kernel without a half-resolution pipeline was measured at full
        // resolution under a quality.json that said half: named, it is an
        // error (as in cavity run); of all kernels, it is left out.
        if (o.half && !supportsHalf(c.kernel)) {
            if (o.kernels.empty()) return {};
            return badInput("--resolution half: " + c.kernel + " has no half-resolution pipeline (measure it at full)");
        }
        c.half = o.half;
        applySwitches(c, o.switches);
        const std::string id = configId(c);
        if (q.filter && !std::regex_search(id, *q.filter)) return {};
        measured.push_back(c);
        const bool sameStep = !steps.empty() && steps.back().options.scenes[0] == c.scene() &&
                              (!q.filter || steps.back().options.kernels[0] == c.kernel);
        if (!sameStep) {
            steps.push_back({o, {}});
            steps.back().options.scenes = {c.scene()};
            steps.back().options.kernels = q.filter ? std::vector{c.kernel} : axes.kernels;
            steps.back().options.samples.clear();
        }
        auto& step = steps.back();
        if (q.filter) step.options.samples.push_back(c.samples());
        else step.options.samples = o.samples;
        step.ids.push_back(id);
        return {};
    }));
    CAVITY_TRY(pipeline::checkSourcesUsed(q.replaced, measured));
    CAVITY_TRY(measure::checkSwitchesUsed(o.switches, measured));
    return steps;
}

Result<std::vector<QualityRow>> runQuality(gpu::Backend& gpu, const std::vector<QualityStep>& steps, bool quiet) {
    std::vector<QualityRow> rows;
    Progress progress(steps.size(), quiet);
    for (const auto& step : steps) {
        progress.start(step.ids.front() + (step.ids.size() > 1 ? " (+" + std::to_string(step.ids.size() - 1) + ")" : ""));
        auto some = measureQuality(gpu, step.options);
        if (!some) {
            progress.interrupt();
            return some.error();
        }
        rows.insert(rows.end(), some->begin(), some->end());
    }
    return rows;
}


// With --kernel-source: the same steps with the committed kernels, and each
// row whose MAE the edit changed labelled with the committed one.
Status markEdited(gpu::Backend& gpu, std::vector<QualityStep> steps, std::vector<QualityRow>& rows, bool quiet) {
    for (auto& step : steps) {
        step.options.overrides.clear();
        step.options.keepImages = false;
    }
    CAVITY_ASSIGN(const auto committed, runQuality(gpu, steps, quiet));
    std::map<std::tuple<std::string, std::string, int>, double> mae;
    for (const auto& r : committed) mae[{r.scene, r.kernel, r.samples}] = r.meanAbsError;
    for (auto& r : rows)
        if (const auto it = mae.find({r.scene, r.kernel, r.samples}); it != mae.end() && it->second != r.meanAbsError)
            r.committedMae = it->second;
    return {};
}

// The parameters set for every kernel measured, as the command line gives
// them: an enum by its choice's name, not its index.
nlohmann::json switchesJson(const kernels::ParamValues& switches) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, value] : switches) {
        const auto* decl = kernels::findParam(name);
        if (decl && decl->type == kernels::ParamType::Enum) out[name] = kernels::valueText(*decl, value);
        else out[name] = value;
    }
    return out;
}

nlohmann::json qualityJson(const QualityRequest& q, const std::string& device, const std::vector<QualityRow>& rows) {
    const auto& o = q.options;
    nlohmann::json doc = {{"schema", "cavity.quality/1"},
                          {"backend", gpu::apiName(q.api)},
                          {"device", device},
                          {"width", o.width},
                          {"height", o.height},
                          {"rays", o.rays},
                          {"blur", o.blur},
                          {"resolution", o.half ? "half" : "full"},
                          {"reach", o.sharedReach ? "shared" : "seed"},
                          {"radius", o.sharedReach ? nlohmann::json(o.radius) : nlohmann::json(nullptr)},
                          {"switches", switchesJson(o.switches)},
                          {"kernel_packages", measure::packagesJson(measure::packagesLoaded())},
                          {"kernel_sources", nlohmann::json::array()},
                          {"rows", nlohmann::json::array()}};
    for (const auto& r : q.replaced) doc["kernel_sources"].push_back({{"name", r.name}, {"file", r.file}, {"digest", r.digest}});
    // Each row's better neighbour in its scene's ranking, when the two cannot be told apart.
    std::vector<size_t> order(rows.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return rows[a].scene != rows[b].scene ? rows[a].scene < rows[b].scene : rows[a].meanAbsError < rows[b].meanAbsError;
    });
    std::map<size_t, std::string> tied;
    for (size_t i = 1; i < order.size(); ++i) {
        const auto &better = rows[order[i - 1]], &worse = rows[order[i]];
        if (better.scene == worse.scene && cannotTellApart(better, worse))
            tied[order[i]] = better.kernel + "/n" + std::to_string(better.samples);
    }
    for (size_t k = 0; k < rows.size(); ++k) {
        const auto& r = rows[k];
        doc["rows"].push_back({{"scene", r.scene},
                               {"kernel", r.kernel},
                               {"samples", r.samples},
                               {"mae", r.meanAbsError},
                               {"mae_low", r.maeLow},
                               {"mae_high", r.maeHigh},
                               {"max_abs", r.maxAbsError},
                               {"mean_ao", r.meanAo},
                               {"mean_truth", r.meanTruth},
                               {"pixels", r.pixels},
                               {"tied_with", tied.count(k) ? nlohmann::json(tied[k]) : nlohmann::json(nullptr)},
                               {"edited", r.committedMae.has_value()},
                               {"committed_mae", r.committedMae ? nlohmann::json(*r.committedMae) : nlohmann::json(nullptr)}});
    }
    return doc;
}


// The screen-space Pareto front and the best within --budget-ms, printed
// and returned for quality.json.
nlohmann::json recommend(const QualityRequest& q, const std::vector<QualityRow>& rows,
                         const std::map<std::pair<std::string, int>, double>& costs, const CostSource& source) {
    const auto all = candidates(rows, costs);
    const auto front = paretoFront(all);
    std::printf("\nscreen-space Pareto front (mean MAE over the scenes against the AO pipeline's time from %s; the SDF "
                "kernels need the scene's distance function and are left out):\n", q.cost.c_str());
    nlohmann::json out = {{"cost_file", q.cost}, {"pareto", nlohmann::json::array()}, {"candidates", nlohmann::json::array()}};
    for (const auto& c : front) {
        std::printf("  %-22s n%-3d MAE %.4f  %.4f ms\n", c.kernel.c_str(), c.samples, c.mae, *c.costMs);
        out["pareto"].push_back(candidateJson(c));
    }
    for (const auto& c : all) out["candidates"].push_back(candidateJson(c));
    if (q.budgetMs) {
        out["budget_ms"] = *q.budgetMs;
        const auto best = bestWithin(all, *q.budgetMs);
        if (best) std::printf("best within %g ms: %s n%d (MAE %.4f, %.4f ms)%s\n", *q.budgetMs, best->kernel.c_str(),
                              best->samples, best->mae, *best->costMs,
                              source.softwareRenderer ? " -- on a software renderer's times: say nothing of a GPU budget"
                                                      : "");
        else std::printf("best within %g ms: none of the screen-space kernels measured fits\n", *q.budgetMs);
        out["best"] = best ? candidateJson(*best) : nlohmann::json(nullptr);
    }
    return out;
}

}  // namespace

// Shared by `cavity quality` and `cavity_render quality` (which runs on the
// GPU machine): one parser, one table, one quality.json.
int qualityCommand(const std::vector<std::string>& argv, const std::string& program) {
    auto failed = [&](const Error& e) { return fail(program, e); };
    auto parsed = parseFlags(qualitySpec(program), argv);
    if (!parsed) return failed(parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    auto q = parseQuality(*parsed);
    if (!q) return failed(q.error());
    auto steps = planQuality(*q);
    if (!steps) return failed(steps.error());
    if (q->filter && steps->empty())
        return failed(badInput("--filter: matches none of the configurations (see " + program + " --list)"));
    if (parsed->has("--list")) {
        for (const auto& step : *steps)
            for (const auto& id : step.ids) std::cout << id << "\n";
        return 0;
    }
    if (auto o = gpu::withEnvironment(q->backend); !o) return failed(o.error());
    if (!q->out.empty()) {
        if (auto st = checkWritableDir("--out", q->out); !st) return failed(st.error());
        // Both files are checked before anything is measured.
        for (const char* name : {"quality.json", "quality.html"}) {
            const std::string file = (std::filesystem::path(q->out) / name).string();
            std::error_code ec;
            if (std::filesystem::exists(std::filesystem::symlink_status(file, ec)) && !std::filesystem::is_regular_file(file, ec))
                return failed(badInput("--out " + q->out + ": " + file + " exists and is not a file"));
        }
    }
    // The cost file is the user's input: read before the backend starts.
    std::map<std::pair<std::string, int>, double> costs;
    CostSource source;
    if (!q->cost.empty()) {
        auto c = loadCosts(q->cost, q->options.half);
        if (!c) return failed(c.error());
        costs = std::move(*c);
        auto s = costSource(q->cost, q->options.half);
        if (!s) return failed(s.error());
        source = std::move(*s);
    }
    auto gpu = gpu::createBackend(q->api, q->backend);
    if (!gpu) return failed(gpu.error());
    const std::string device = (*gpu)->info().deviceName;
    std::cerr << program << ": " << gpu::apiName(q->api) << ": " << device << "\n";
    // The images travel to quality.html's error maps.
    for (auto& step : *steps) step.options.keepImages = !q->out.empty();
    auto rows = runQuality(**gpu, *steps, parsed->has("--quiet"));
    if (!rows) return failed(rows.error());
    if (!q->replaced.empty())
        if (auto st = markEdited(**gpu, *steps, *rows, parsed->has("--quiet")); !st) return failed(st.error());
    // A cost file that times none of the kernels measured recommends
    // nothing: "none fits" would read as a verdict.
    if (!costs.empty() && std::none_of(rows->begin(), rows->end(), [&](const QualityRow& r) {
            return costs.count({r.kernel, r.samples}) > 0;
        }))
        return failed(badInput("--cost " + q->cost + ": times none of the kernels measured at their sample counts "
                               "(run it with the same --kernel and --samples)"));
    printQuality(q->options, *rows, costs);
    if (!costs.empty()) std::printf("%s\n", source.text.c_str());
    nlohmann::json doc = qualityJson(*q, device, *rows);
    if (!costs.empty()) {
        doc["recommendation"] = recommend(*q, *rows, costs, source);
        doc["cost_source"] = {{"text", source.text}, {"software_renderer", source.softwareRenderer}};
    }
    // An AO of NaN or infinity has no error to rank: the table and the
    // files still say so, and the exit code fails it as `cavity run` does.
    const auto nonFinite = [&] {
        int n = 0;
        for (const auto& r : *rows)
            if (!std::isfinite(r.meanAbsError) || !std::isfinite(r.meanAo))
                ++n, std::fprintf(stderr, "%s: %s/%s/n%d: the AO holds NaN or infinity (MAE %g)\n", program.c_str(),
                                  r.scene.c_str(), r.kernel.c_str(), r.samples, r.meanAbsError);
        return n ? 1 : 0;
    };
    if (q->out.empty()) return nonFinite();
    std::error_code ec;
    std::filesystem::create_directories(q->out, ec);
    // The page first, quality.json last: the record a reader takes the
    // folder by is written when everything else is.
    const std::string path = (std::filesystem::path(q->out) / "quality.json").string();
    const std::string page = (std::filesystem::path(q->out) / "quality.html").string();
    if (auto st = core::writeFileAtomically(page, qualityPage(doc, *rows)); !st) return failed(st.error());
    if (auto st = writeJson(path, doc); !st) return failed(st.error());
    std::printf("\nwrote %s and %s (every kernel's AO and error map beside the truth)\n", path.c_str(), page.c_str());
    return nonFinite();
}

}  // namespace cavity::flags
