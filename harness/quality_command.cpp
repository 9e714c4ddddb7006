// `cavity quality`: each AO kernel's error against the ray-traced ground
// truth, as a table on stdout and quality.json.
#include "cli.h"
#include "quality.h"
#include "results.h"
#include "runner.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace cavity::cli {

namespace {

std::string usage(const std::string& program) {
    const std::string pad(program.size(), ' ');
    return "usage: " + program + " [--backend gl|vk] [--scene S[,S..]] [--kernel K[,K..]] [--samples N[,N..]]\n" +
           "       " + pad + " [--res WxH] [--rays N] [--resolution full|half] [--reach seed|shared] [--radius R]\n" +
           "       " + pad + " [--device K] [--out DIR]\n" +
           "mean absolute error of each AO kernel (raw AO, no bilateral blur) against the ground truth\n" +
           "--reach seed (default): each kernel at its own default reach, the truth at 0.5;\n" +
           "--reach shared: every kernel and the truth at --radius (default 0.5; --radius implies shared)\n";
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
    bool reachGiven = false, radiusGiven = false;
    Args a(argv);
    while (!a.done()) {
        const std::string flag = a.next();
        if (flag == "--help" || flag == "-h") {
            std::cout << usage(program);
            return 0;
        }
        auto v = a.value(flag);
        if (!v) return fail(v.error());
        if (flag == "--backend") {
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
                if (!d || d->role != "ao") return fail(badInput("--kernel " + k + ": not an AO kernel (see cavity run --help)"));
            }
        } else if (flag == "--samples") {
            o.samples.clear();
            auto items = splitList(flag, *v);
            if (!items) return fail(items.error());
            for (const auto& s : *items) {
                auto n = parseInt("--samples", s, 1, 256);
                if (!n) return fail(n.error());
                o.samples.push_back(*n);
            }
        } else if (flag == "--res") {
            auto wh = parseResolution("--res", *v);
            if (!wh) return fail(wh.error());
            std::tie(o.width, o.height) = *wh;
        } else if (flag == "--rays") {
            auto n = parseInt("--rays", *v, 1024, 65536);
            if (!n) return fail(n.error());
            o.rays = *n;
        } else if (flag == "--resolution") {
            if (*v != "full" && *v != "half") return fail(badInput("--resolution " + *v + ": must be full or half"));
            o.half = *v == "half";
        } else if (flag == "--reach") {
            if (*v != "seed" && *v != "shared") return fail(badInput("--reach " + *v + ": must be seed or shared"));
            o.sharedReach = *v == "shared";
            reachGiven = true;
        } else if (flag == "--radius") {
            auto r = parseNumber("--radius", *v, 1e-6, 100);
            if (!r) return fail(r.error());
            o.radius = *r;
            radiusGiven = true;
        } else if (flag == "--device") {
            auto n = parseInt("--device", *v, 0, 64);
            if (!n) return fail(n.error());
            backend.deviceIndex = *n;
        } else if (flag == "--out") {
            out = *v;
        } else {
            return fail(badInput(flag + ": unknown flag (see " + program + " --help)"));
        }
    }
    if (radiusGiven) {
        if (reachGiven && !o.sharedReach)
            return fail(badInput("--radius " + std::to_string(o.radius) + ": only with --reach shared"));
        o.sharedReach = true;
    }
    if (!out.empty())
        if (auto st = checkWritableDir("--out", out); !st) return fail(st.error());

    auto gpu = gpu::createBackend(api, backend);
    if (!gpu) return fail(gpu.error());
    std::cerr << program << ": " << gpu::apiName(api) << ": " << (*gpu)->info().deviceName << "\n";
    auto rows = measureQuality(**gpu, o);
    if (!rows) return fail(rows.error());

    const std::string reach = o.sharedReach ? "shared" : "seed";
    if (o.sharedReach)
        std::printf("reach: shared, every kernel and the truth at R = %g\n", o.radius);
    else
        std::printf("reach: seed, each kernel at its own default reach, the truth at R = 0.5\n");
    std::printf("%-8s %-20s %7s %8s %8s %8s %8s\n", "scene", "kernel", "samples", "MAE", "max", "mean AO", "truth");
    nlohmann::json doc = {{"schema", "cavity-quality/1"},
                          {"backend", gpu::apiName(api)},
                          {"device", (*gpu)->info().deviceName},
                          {"width", o.width},
                          {"height", o.height},
                          {"rays", o.rays},
                          {"resolution", o.half ? "half" : "full"},
                          {"reach", reach},
                          {"radius", o.sharedReach ? nlohmann::json(o.radius) : nlohmann::json(nullptr)},
                          {"rows", nlohmann::json::array()}};
    for (const auto& r : *rows) {
        std::printf("%-8s %-20s %7d %8.4f %8.4f %8.4f %8.4f\n", r.scene.c_str(), r.kernel.c_str(), r.samples,
                    r.meanAbsError, r.maxAbsError, r.meanAo, r.meanTruth);
        doc["rows"].push_back({{"scene", r.scene},
                               {"kernel", r.kernel},
                               {"samples", r.samples},
                               {"mae", r.meanAbsError},
                               {"max_abs", r.maxAbsError},
                               {"mean_ao", r.meanAo},
                               {"mean_truth", r.meanTruth},
                               {"pixels", r.pixels}});
    }
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
