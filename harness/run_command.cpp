// `cavity run`: a sweep of configurations on one or both backends, with
// images, results.json and a timing table on stdout.
#include "cli.h"
#include "gbuffer_import.h"
#include "runner.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace cavity::cli {

namespace {

constexpr const char* kRunUsage =
    "usage: cavity run [--backend gl|vk|all] [--scene S[,S..]] [--kernel K[,K..]] [--samples N[,N..]]\n"
    "                  [--blur R[,R..]] [--resolution full|half[,..]] [--res WxH[,WxH..]]\n"
    "                  [--stage compute|fragment[,..]] [--gbuffer sdf|raster|import[,..]] [--gbuffer-file FILE.exr]\n"
    "                  [--frames N] [--warmup N] [--timing batch|drained] [--max-noise PCT] [--max-time S]\n"
    "                  [--device K]\n"
    "                  [--validation] [--out DIR] [--<kernel parameter> VALUE ...]\n";

struct Sweep {
    std::vector<std::string> backends{"all"};
    std::vector<std::string> kernels{"alchemy"};
    std::vector<std::string> scenes{"corner"};
    std::vector<std::string> samples, blurs;
    std::vector<std::string> resolutions{"full"};
    std::vector<std::pair<int, int>> sizes{{320, 180}};
    std::vector<gpu::Stage> stages{gpu::Stage::Compute};
    std::vector<std::string> gbuffers{"sdf"};
    std::string gbufferFile;          // --gbuffer-file
    bool sizeGiven = false, sceneGiven = false;
    RunConfig base;
    RunOptions options;
    gpu::BackendOptions backend;
    std::string out = "out";
};

Result<Sweep> parse(const std::vector<std::string>& argv) {
    Sweep s;
    Args a(argv);
    while (!a.done()) {
        const std::string flag = a.next();
        if (flag == "--validation") { s.backend.validation = true; continue; }
        if (flag == "--help" || flag == "-h") return badInput(kRunUsage);
        if (flag.rfind("--", 0) != 0) return badInput("'" + flag + "': unexpected argument (flags start with --; see cavity run --help)");
        CAVITY_ASSIGN(const std::string v, a.value(flag));
        if (flag == "--backend") {
            CAVITY_ASSIGN(s.backends, splitList(flag, v));
            for (const auto& b : s.backends)
                if (b != "gl" && b != "vk" && b != "all") return badInput("--backend " + b + ": must be gl, vk or all");
        } else if (flag == "--kernel") {
            CAVITY_ASSIGN(s.kernels, splitList(flag, v));
        } else if (flag == "--scene") {
            CAVITY_ASSIGN(s.scenes, splitList(flag, v));
            s.sceneGiven = true;
        } else if (flag == "--samples") {
            CAVITY_ASSIGN(s.samples, splitList(flag, v));
        } else if (flag == "--blur") {
            CAVITY_ASSIGN(s.blurs, splitList(flag, v));
        } else if (flag == "--resolution") {
            CAVITY_ASSIGN(s.resolutions, splitList(flag, v));
            for (const auto& r : s.resolutions)
                if (r != "full" && r != "half") return badInput("--resolution " + r + ": must be full or half");
        } else if (flag == "--res") {
            s.sizeGiven = true;
            s.sizes.clear();
            CAVITY_ASSIGN(const auto items, splitList(flag, v));
            for (const auto& r : items) {
                CAVITY_ASSIGN(auto wh, parseResolution("--res", r));
                s.sizes.push_back(wh);
            }
        } else if (flag == "--gbuffer") {
            CAVITY_ASSIGN(s.gbuffers, splitList(flag, v));
            for (const auto& g : s.gbuffers)
                if (g != "sdf" && g != "raster" && g != "import")
                    return badInput("--gbuffer " + g + ": must be sdf, raster or import");
        } else if (flag == "--gbuffer-file") {
            if (v.empty()) return badInput("--gbuffer-file: missing value");
            s.gbufferFile = v;
        } else if (flag == "--stage") {
            s.stages.clear();
            CAVITY_ASSIGN(const auto items, splitList(flag, v));
            for (const auto& st : items) {
                if (st == "compute") s.stages.push_back(gpu::Stage::Compute);
                else if (st == "fragment") s.stages.push_back(gpu::Stage::Fragment);
                else return badInput("--stage " + st + ": must be compute or fragment");
            }
        } else if (flag == "--frames") {
            CAVITY_ASSIGN(s.options.frames, parseInt(flag, v, 1, 100000));
        } else if (flag == "--warmup") {
            CAVITY_ASSIGN(s.options.warmup, parseInt(flag, v, 0, 10000));
        } else if (flag == "--timing") {
            if (v != "batch" && v != "drained") return badInput("--timing " + v + ": must be batch or drained");
            s.options.mode = v == "batch" ? TimingMode::Batch : TimingMode::Drained;
        } else if (flag == "--max-noise") {
            CAVITY_ASSIGN(const double pct, parseNumber(flag, v, 0, 100));
            s.options.maxNoise = pct / 100;
        } else if (flag == "--max-time") {
            CAVITY_ASSIGN(s.options.maxSeconds, parseNumber(flag, v, 0.001, 3600));
        } else if (flag == "--device") {
            CAVITY_ASSIGN(s.backend.deviceIndex, parseInt(flag, v, 0, 64));
        } else if (flag == "--out") s.out = v;
        else if (isKernelParam(flag.substr(2))) {
            CAVITY_TRY(setParam(s.base, flag.substr(2), v));
        } else return badInput(flag + ": unknown flag (see cavity run --help)");
    }
    const bool import = std::find(s.gbuffers.begin(), s.gbuffers.end(), "import") != s.gbuffers.end();
    if (import && s.gbufferFile.empty())
        return badInput("--gbuffer import: needs --gbuffer-file FILE (a multi-channel OpenEXR capture)");
    if (!import && !s.gbufferFile.empty())
        return badInput("--gbuffer-file " + s.gbufferFile + ": only used with --gbuffer import");
    const bool onlyImport =
        std::all_of(s.gbuffers.begin(), s.gbuffers.end(), [](const std::string& g) { return g == "import"; });
    if (onlyImport && s.sceneGiven)
        return badInput("--scene " + s.scenes[0] + ": not used with --gbuffer import (the capture is the scene)");
    return s;
}

// Expands the sweep axes into validated configurations (API left unset).
Result<std::vector<RunConfig>> expand(const Sweep& s) {
    std::vector<RunConfig> out;
    const std::vector<std::string> none{""};
    for (const auto& scene : s.scenes)
        for (const auto& kernel : s.kernels)
            for (const auto& n : s.samples.empty() ? none : s.samples)
                for (const auto& b : s.blurs.empty() ? none : s.blurs)
                    for (const auto& res : s.resolutions)
                        for (const auto& [w, h] : s.sizes)
                            for (auto stage : s.stages)
                            for (const auto& gbuffer : s.gbuffers) {
                                RunConfig c = s.base;
                                c.raster = gbuffer == "raster";
                                c.kernel = kernel;
                                if (gbuffer == "import") {
                                    // The capture is the scene: one configuration, whatever --scene says.
                                    if (scene != s.scenes.front()) continue;
                                    c.gbufferFile = s.gbufferFile;
                                } else {
                                    CAVITY_TRY(setParam(c, "scene", scene));
                                }
                                if (!n.empty()) CAVITY_TRY(setParam(c, "samples", n));
                                if (!b.empty()) CAVITY_TRY(setParam(c, "blur", b));
                                c.half = res == "half";
                                c.width = w;
                                c.height = h;
                                c.stage = stage;
                                // A sweep skips the combinations a kernel lacks (SSDO at
                                // half resolution); asked for alone, they are an error.
                                const bool alone = s.kernels.size() == 1 && s.resolutions.size() == 1;
                                if (c.half && !supportsHalf(c.kernel) && !alone) continue;
                                CAVITY_TRY(validate(c));
                                out.push_back(c);
                            }
    return out;
}

void printTable(const std::vector<RunRecord>& runs) {
    std::printf("\n%-52s %-10s %10s %10s %10s %7s  %s\n", "configuration", "pass", "median ms", "min ms", "p90 ms",
                "CV", "clock");
    for (const auto& r : runs) {
        const std::string id = configId(r.config);
        auto row = [&](const std::string& name, const Stats& st) {
            std::printf("%-52s %-10s %10.3f %10.3f %10.3f %6.1f%%  %s/%s\n", id.c_str(), name.c_str(), st.median,
                        st.min, st.p90, 100.0 * st.cv, r.timing.clock.c_str(), timingModeName(r.timing.mode));
        };
        for (const auto& p : r.timing.passes) row(p.name, p.stats);
        row("frame", r.timing.frame.stats);
    }
    for (const auto& r : runs) {
        const auto& t = r.timing;
        const std::string id = configId(r.config);
        if (t.rejectedFrames)
            std::printf("note: %s: %d frames failed the clock check and were left out (%s)\n", id.c_str(),
                        t.rejectedFrames, t.rejectedNote.c_str());
        if (t.steadyChecked && !t.steady)
            std::printf("note: %s: the frame time was not steady after %.1f s of warm-up\n", id.c_str(),
                        t.warmupSeconds);
        if (!t.clocks.source.empty())
            std::printf("clocks: %s: SM %.0f MHz (%.0f..%.0f), memory %.0f MHz%s\n", id.c_str(), t.clocks.smMedian,
                        t.clocks.smMin, t.clocks.smMax, t.clocks.memMedian,
                        t.clocks.moved() ? ": the SM clock moved during the measurement" : "");
    }
    for (const auto& r : runs)
        if (!r.timing.clockNote.empty())
            std::printf("note: %s %s: %s\n", gpu::apiName(r.config.api), r.device.deviceName.c_str(),
                        r.timing.clockNote.c_str());
}

}  // namespace

int runCommand(const std::vector<std::string>& argv) {
    auto parsed = parse(argv);
    if (!parsed) {
        std::cerr << "cavity run: " << parsed.error().message << "\n";
        return exitCode(parsed.error());
    }
    Sweep& s = *parsed;
    // An imported G-buffer is read here, before anything runs or is written;
    // without --res the run takes the capture's size.
    std::map<std::pair<int, int>, std::shared_ptr<const GBufferImages>> captures;
    if (!s.gbufferFile.empty() && !s.sizeGiven) {
        auto g = importGBuffer(s.gbufferFile);
        if (!g) {
            std::cerr << "cavity run: " << g.error().message << "\n";
            return exitCode(g.error());
        }
        const std::pair<int, int> size{g->position.width, g->position.height};
        s.sizes = {size};
        captures[size] = std::make_shared<const GBufferImages>(std::move(*g));
    }
    auto configs = expand(s);
    if (!configs) {
        std::cerr << "cavity run: " << configs.error().message << "\n";
        return exitCode(configs.error());
    }
    for (auto& c : *configs) {
        if (!c.imported()) continue;
        auto& images = captures[{c.width, c.height}];
        if (!images) {
            auto g = importGBuffer(c.gbufferFile, c.width, c.height);
            if (!g) {
                std::cerr << "cavity run: " << g.error().message << "\n";
                return exitCode(g.error());
            }
            images = std::make_shared<const GBufferImages>(std::move(*g));
        }
        c.gbufferImages = images;
    }
    if (auto st = checkWritableDir("--out", s.out); !st) {
        std::cerr << "cavity run: " << st.error().message << "\n";
        return exitCode(st.error());
    }
    std::vector<gpu::Api> apis;
    for (const auto& b : s.backends) {
        if (b == "gl" || b == "all") apis.push_back(gpu::Api::OpenGL);
        if (b == "vk" || b == "all") apis.push_back(gpu::Api::Vulkan);
    }

    std::vector<RunRecord> runs;
    std::vector<RunError> errors;
    int worst = 0;
    std::string command = "cavity run";
    for (const auto& a : argv) command += " " + a;
    s.options.outDir = s.out;
    for (auto api : apis) {
        auto backend = gpu::createBackend(api, s.backend);
        if (!backend) {
            std::cerr << "cavity run: " << backend.error().message << "\n";
            errors.push_back({gpu::apiName(api), exitCode(backend.error()), backend.error().message});
            worst = std::max(worst, exitCode(backend.error()));
            continue;
        }
        auto& gpu = **backend;
        std::cerr << "cavity run: " << gpu::apiName(api) << ": " << gpu.info().deviceName << " (" << gpu.info().driver
                  << ")\n";
        for (auto c : *configs) {
            c.api = api;
            auto r = runConfig(gpu, c, s.options);
            if (!r) {
                std::cerr << "cavity run: " << configId(c) << ": " << r.error().message << "\n";
                errors.push_back({gpu::apiName(api), exitCode(r.error()), configId(c) + ": " + r.error().message});
                worst = std::max(worst, exitCode(r.error()));
                continue;
            }
            for (const auto& m : r->debugMessages) std::cerr << "cavity run: " << gpu::apiName(api) << " debug: " << m << "\n";
            // Exit 1: the run finished, but a pass wrote NaN or infinity
            // (README, Exit codes); its images and results are still written.
            for (const auto& n : r->nonFinite) {
                std::cerr << "cavity run: " << configId(c) << ": " << n.message() << "\n";
                worst = std::max(worst, int(ErrorCode::Regression));
            }
            runs.push_back(std::move(*r));
        }
    }
    if (!runs.empty()) printTable(runs);
    if (!runs.empty() || !errors.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(s.out, ec);
        const std::string path = (std::filesystem::path(s.out) / "results.json").string();
        if (auto st = writeJson(path, resultsDocument(runs, errors, command)); !st) {
            std::cerr << "cavity run: " << st.error().message << "\n";
            return exitCode(st.error());
        }
        std::printf("\nwrote %s\n", path.c_str());
    }
    return worst;
}

}  // namespace cavity::cli
