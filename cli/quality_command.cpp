// `cavity quality`: each AO kernel's error against the ray-traced ground
// truth, as a table on stdout and quality.json.
#include "cli.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "core/progress.h"
#include "measure/quality.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "core/text_table.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>

namespace cavity::cli {

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
        {"--reach", "seed|shared", "seed (default): each kernel at its own default reach, the truth at 0.5; "
                                   "shared: every kernel and the truth at --radius"},
        {"--radius", "R", "the shared reach (default 0.5; implies --reach shared)"},
        {"--blur", "R", "compare the AO after the pipeline's blur of radius R, " + kernels::allowedValues(*kernels::findParam("blur")) + " (default 0, the raw AO)"},
        {"--device", "K", "device index (0..64)"},
        {"--out", "DIR", "also write DIR/quality.json"},
        {"--filter", "REGEX", "only the configurations whose id matches (searched; ids as --list prints them)"},
        {"--list", "", "print the configuration ids this would measure, one a line, and measure nothing"},
        {"--quiet", "", "no progress lines on stderr"},
    };
    return c;
}

}  // namespace

// Shared by `cavity quality` and `cavity_render quality` (which runs on the
// GPU machine): one parser, one table, one quality.json.
int qualityCommand(const std::vector<std::string>& argv, const std::string& program) {
    auto fail = [&](const Error& e) {
        std::cerr << program << ": " << e.message << "\n";
        return exitCode(e);
    };
    QualityOptions o;
    gpu::Api api = gpu::Api::Vulkan;
    gpu::BackendOptions backend;
    std::string out;
    std::optional<std::regex> filter;
    auto parsed = parseFlags(qualitySpec(program), argv);
    if (!parsed) return fail(parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    bool reachGiven = false, radiusGiven = false;
    for (const auto& [flag, value] : parsed->values) {
        const std::optional<std::string> v = value;
        if (flag == "--reach") {
            if (*v != "seed" && *v != "shared") return fail(badInput("--reach " + *v + ": must be seed or shared"));
            o.sharedReach = *v == "shared";
            reachGiven = true;
        } else if (flag == "--radius") {
            auto r = kernels::parseValue(*kernels::findParam("radius"), *v);
            if (!r) return fail(r.error());
            o.radius = *r;
            radiusGiven = true;
        } else if (flag == "--backend") {
            if (*v != "gl" && *v != "vk") return fail(badInput("--backend " + *v + ": must be gl or vk"));
            api = *v == "gl" ? gpu::Api::OpenGL : gpu::Api::Vulkan;
        } else if (flag == "--scene") {
            auto items = splitList(flag, *v);
            if (!items) return fail(items.error());
            o.scenes = *items;
            for (const auto& s : o.scenes) {
                RunConfig probe;
                if (auto st = setParam(probe, "scene", s); !st) return fail(st.error());
            }
        } else if (flag == "--kernel") {
            auto items = splitList(flag, *v);
            if (!items) return fail(items.error());
            o.kernels = *items;
            for (const auto& k : o.kernels) {
                const auto* d = kernels::find(k);
                if (!d || d->role != kernels::Role::Ao) return fail(badInput("--kernel " + k + ": not an AO kernel (see cavity run --help)"));
            }
        } else if (flag == "--samples") {
            o.samples.clear();
            auto items = splitList(flag, *v);
            if (!items) return fail(items.error());
            for (const auto& s : *items) {
                auto n = kernels::parseValue(*kernels::findParam("samples"), s);
                if (!n) return fail(n.error());
                o.samples.push_back(kernels::asInt(*n));
            }
        } else if (flag == "--res") {
            auto wh = parseResolution("--res", *v);
            if (!wh) return fail(wh.error());
            std::tie(o.width, o.height) = *wh;
        } else if (flag == "--blur") {
            auto r = kernels::parseValue(*kernels::findParam("blur"), *v);
            if (!r) return fail(r.error());
            o.blur = kernels::asInt(*r);
        } else if (flag == "--rays") {
            auto n = kernels::parseValue(*kernels::findParam("rays"), *v);
            if (!n) return fail(n.error());
            o.rays = kernels::asInt(*n);
        } else if (flag == "--resolution") {
            if (*v != "full" && *v != "half") return fail(badInput("--resolution " + *v + ": must be full or half"));
            o.half = *v == "half";
        } else if (flag == "--device") {
            auto n = parseInt("--device", *v, 0, 64);
            if (!n) return fail(n.error());
            backend.deviceIndex = *n;
        } else if (flag == "--out") {
            out = *v;
        } else if (flag == "--filter") {
            try {
                filter.emplace(*v);
            } catch (const std::regex_error& e) {
                return fail(badInput("--filter " + *v + ": not a regular expression (" + e.what() + ")"));
            }
        }
    }
    if (radiusGiven) {
        if (reachGiven && !o.sharedReach)
            return fail(badInput("--radius " + std::to_string(o.radius) + ": only with --reach shared"));
        o.sharedReach = true;
    }
    // The configurations measured, as ids: what measureQuality renders for
    // each (scene, kernel, samples), the raw AO with the bilateral off.
    std::vector<std::string> names = o.kernels;
    if (names.empty())
        for (const auto& k : kernels::all())
            if (k.role == kernels::Role::Ao) names.push_back(k.name);
    struct Step {
        QualityOptions options;   // one scene, one kernel or all, the selected sample counts
        std::vector<std::string> ids;
    };
    std::vector<Step> steps;
    size_t total = 0;
    for (const auto& scene : o.scenes) {
        // Without --filter one step a scene (its ground truth is rendered
        // once); with it one step a kernel, holding the sample counts selected.
        Step whole{o, {}};
        whole.options.scenes = {scene};
        whole.options.kernels = names;
        for (const auto& kernel : names) {
            Step step{o, {}};
            step.options.scenes = {scene};
            step.options.kernels = {kernel};
            step.options.samples.clear();
            for (int n : o.samples) {
                RunConfig c;
                c.api = api;
                c.kernel = kernel;
                c.width = o.width;
                c.height = o.height;
                c.params["blur"] = o.blur;
                c.params["samples"] = n;
                if (auto st = setParam(c, "scene", scene); !st) return fail(st.error());
                c.half = o.half && supportsHalf(kernel);
                c.stage = o.stage;
                const std::string id = configId(c);
                if (filter && !std::regex_search(id, *filter)) continue;
                step.options.samples.push_back(n);
                step.ids.push_back(id);
                whole.ids.push_back(id);
            }
            if (filter && !step.ids.empty()) steps.push_back(step);
        }
        if (!filter) steps.push_back(whole);
        total += whole.ids.size();
    }
    if (filter && total == 0) return fail(badInput("--filter: matches none of the configurations (see " + program + " --list)"));
    if (parsed->has("--list")) {
        for (const auto& step : steps)
            for (const auto& id : step.ids) std::cout << id << "\n";
        return 0;
    }
    if (!out.empty())
        if (auto st = checkWritableDir("--out", out); !st) return fail(st.error());

    auto gpu = gpu::createBackend(api, backend);
    if (!gpu) return fail(gpu.error());
    std::cerr << program << ": " << gpu::apiName(api) << ": " << (*gpu)->info().deviceName << "\n";
    std::vector<QualityRow> rows;
    {
        Progress progress(steps.size(), parsed->has("--quiet"));
        for (const auto& step : steps) {
            progress.start(step.ids.front() + (step.ids.size() > 1 ? " (+" + std::to_string(step.ids.size() - 1) + ")" : ""));
            auto some = measureQuality(**gpu, step.options);
            if (!some) {
                progress.interrupt();
                return fail(some.error());
            }
            rows.insert(rows.end(), some->begin(), some->end());
        }
    }

    const std::string reach = o.sharedReach ? "shared" : "seed";
    if (o.sharedReach)
        std::printf("reach: shared, every kernel and the truth at R = %g\n", o.radius);
    else
        std::printf("reach: seed, each kernel at its own default reach, the truth at R = 0.5\n");
    using A = TextTable::Align;
    TextTable table({{"scene", A::Left}, {"kernel", A::Left}, {"samples", A::Right}, {"MAE", A::Right}, {"max", A::Right},
                     {"mean AO", A::Right}, {"truth", A::Right}});
    nlohmann::json doc = {{"schema", "cavity-quality/1"},
                          {"backend", gpu::apiName(api)},
                          {"device", (*gpu)->info().deviceName},
                          {"width", o.width},
                          {"height", o.height},
                          {"rays", o.rays},
                          {"blur", o.blur},
                          {"resolution", o.half ? "half" : "full"},
                          {"reach", reach},
                          {"radius", o.sharedReach ? nlohmann::json(o.radius) : nlohmann::json(nullptr)},
                          {"rows", nlohmann::json::array()}};
    for (const auto& r : rows) {
        table.add({r.scene, r.kernel, std::to_string(r.samples), TextTable::number(r.meanAbsError, 4),
                   TextTable::number(r.maxAbsError, 4), TextTable::number(r.meanAo, 4), TextTable::number(r.meanTruth, 4)});
        doc["rows"].push_back({{"scene", r.scene},
                               {"kernel", r.kernel},
                               {"samples", r.samples},
                               {"mae", r.meanAbsError},
                               {"max_abs", r.maxAbsError},
                               {"mean_ao", r.meanAo},
                               {"mean_truth", r.meanTruth},
                               {"pixels", r.pixels}});
    }
    table.print();
    if (!out.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(out, ec);
        const std::string path = (std::filesystem::path(out) / "quality.json").string();
        if (auto st = writeJson(path, doc); !st) return fail(st.error());
        std::printf("\nwrote %s\n", path.c_str());
    }
    return 0;
}

}  // namespace cavity::cli
