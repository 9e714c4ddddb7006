// `cavity run`: a sweep of configurations on one or both backends, with
// images, results.json and a timing table on stdout.
#include "cli.h"
#include "pipeline/config_id.h"
#include "images/gbuffer_import.h"
#include "core/progress.h"
#include "measure/runner.h"
#include "core/text_table.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <regex>

namespace cavity::cli {

namespace {

// The flags of cavity run, declared once: --help, the parse and the README's
// flag table (tests/readme_flags.py checks it against --help) read this.
const CommandSpec& runSpec() {
    static const CommandSpec spec = [] {
        CommandSpec c;
        c.program = "cavity run";
        c.description =
            "Runs a sweep of kernel configurations on one or both backends: images under --out/<id>/, "
            "results.json, a timing table on stdout, progress on stderr. Every list flag takes "
            "VALUE[,VALUE..] and the sweep is the product of all lists.";
        const std::string sweep = "Sweep", timing = "Timing", output = "Device and output";
        const std::string scenes = kernels::findParam("scene")->help;
        c.flags = {
            {"--backend", "gl|vk|all[,..]", "backends to run on (default all)", sweep},
            {"--kernel", "K[,K..]", "AO kernels (default alchemy; listed below)", sweep},
            {"--scene", "S[,S..]", scenes + " (default corner)", sweep},
            {"--resolution", "full|half[,..]", "AO at full or half resolution with a bilateral upsample (default full)", sweep},
            {"--res", "WxH[,WxH..]", "image sizes (default 320x180; with --gbuffer import, the capture's)", sweep},
            {"--stage", "compute|fragment[,..]", "shader stage of every pass (default compute)", sweep},
            {"--gbuffer", "sdf|raster|import[,..]", "G-buffer source: ray-marched, rasterised meshes, or a capture (default sdf)", sweep},
            {"--gbuffer-file", "FILE.exr", "the capture for --gbuffer import (multi-channel OpenEXR)", sweep},
            {"--filter", "REGEX", "run only the configurations whose id matches (searched, as gate and cavity_bench do)", sweep},
            {"--frames", "N", "measured frames, at least (1..100000; default 50)", timing},
            {"--warmup", "N", "warm-up frames, at least (0..10000; default 5)", timing},
            {"--timing", "batch|drained", "batch: back-to-back frames; drained: wait for the GPU after each (default: the device's)", timing},
            {"--max-noise", "PCT", "stop measuring once the median's noise is under PCT percent (0..100; 0: a fixed count)", timing},
            {"--max-time", "S", "stop measuring after S seconds (0.001..3600)", timing},
            {"--device", "K", "device index (0..64; default 0)", output},
            {"--validation", "", "enable the Vulkan validation layers and the GL debug output", output},
            {"--out", "DIR", "output folder (default out)", output},
            {"--list", "", "print the configuration ids this run would measure, one a line, and run nothing", output},
            {"--quiet", "", "no progress lines on stderr", output},
        };
        for (auto& f : kernelParamFlags({"scene"})) c.flags.push_back(std::move(f));
        c.footer = "\n" + kernelHelp() +
                   "\nIds read scene/kernel/nSAMPLES/bBLUR[/param=value..]/full|half/WxH/api/stage "
                   "(README, Configuration ids). Exit codes: 0 ok, 1 NaN written, 2 bad usage, 3 no backend, 4 GPU error.";
        return c;
    }();
    return spec;
}

struct Sweep {
    std::vector<std::string> backends{"all"};
    std::vector<std::string> kernels{"alchemy"};
    std::vector<std::string> scenes{"corner"};
    // Every kernel parameter given (--samples, --blur, --radius, ...): one
    // axis each, its values in the order given.
    std::map<std::string, std::vector<double>> params;
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
    bool list = false, quiet = false;
    std::optional<std::regex> filter;   // --filter
    std::string filterText;
    std::string helpText;               // --help: print this, run nothing
};

Result<Sweep> parse(const std::vector<std::string>& argv) {
    Sweep s;
    CAVITY_ASSIGN(const ParsedFlags parsed, parseFlags(runSpec(), argv));
    if (parsed.help) {
        s.helpText = parsed.helpText;
        return s;
    }
    s.backend.validation = parsed.has("--validation");
    s.list = parsed.has("--list");
    s.quiet = parsed.has("--quiet");
    for (const auto& [flag, v] : parsed.values) {
        if (flag == "--backend") {
            CAVITY_ASSIGN(s.backends, splitList(flag, v));
            for (const auto& b : s.backends)
                if (b != "gl" && b != "vk" && b != "all") return badInput("--backend " + b + ": must be gl, vk or all");
        } else if (flag == "--kernel") {
            CAVITY_ASSIGN(s.kernels, splitList(flag, v));
        } else if (flag == "--scene") {
            CAVITY_ASSIGN(s.scenes, splitList(flag, v));
            s.sceneGiven = true;
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
        else if (flag == "--filter") {
            try {
                s.filter.emplace(v);
            } catch (const std::regex_error& e) {
                return badInput("--filter " + v + ": not a regular expression (" + e.what() + ")");
            }
            s.filterText = v;
        } else if (isKernelParam(flag.substr(2))) {
            // Every kernel parameter sweeps: --radius 0.5,1.0 is two configurations.
            // Each value is parsed and checked once, here (kernels/params.h).
            CAVITY_ASSIGN(auto items, splitList(flag, v));
            const auto& decl = *kernels::findParam(flag.substr(2));
            std::vector<double> values;
            for (const auto& item : items) {
                CAVITY_ASSIGN(double x, kernels::parseValue(decl, item));
                if (std::find(values.begin(), values.end(), x) != values.end())
                    return badInput(flag + " '" + v + "': " + item + " is a value given twice");
                values.push_back(x);
            }
            s.params[flag.substr(2)] = std::move(values);
        }
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
    // The kernel parameters' product, each point a set of (name, value) pairs.
    std::vector<std::vector<std::pair<std::string, double>>> points{{}};
    for (const auto& [name, values] : s.params) {
        std::vector<std::vector<std::pair<std::string, double>>> next;
        for (const auto& point : points)
            for (const auto& v : values) {
                auto p = point;
                p.emplace_back(name, v);
                next.push_back(std::move(p));
            }
        points = std::move(next);
    }
    std::vector<RunConfig> out;
    for (const auto& scene : s.scenes)
        for (const auto& kernel : s.kernels)
            for (const auto& point : points)
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
                                for (const auto& [name, v] : point) c.params[name] = v;
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

// A CV above this is flagged in the table: the timing was noisy enough that
// the median may move by more than a kernel change one wants to see.
constexpr double kNoisyCv = 0.10;

void printTable(const std::vector<RunRecord>& runs) {
    auto clockOf = [](const RunRecord& r) { return r.timing.clock + "/" + timingModeName(r.timing.mode); };
    // The clock most configurations used is said once; each that differs is named.
    std::map<std::string, int> clockCount;
    for (const auto& r : runs) ++clockCount[clockOf(r)];
    std::string clock;
    int most = 0;
    for (const auto& [c, n] : clockCount)
        if (n > most) most = n, clock = c;
    std::printf("\nclock: %s%s\n", clock.c_str(), clockCount.size() == 1 ? " (every configuration)" : " (except as noted below)");
    using A = TextTable::Align;
    TextTable table({{"configuration", A::Left}, {"pass", A::Left}, {"median ms", A::Right}, {"min ms", A::Right},
                     {"p90 ms", A::Right}, {"CV", A::Right}},
                    "  ");
    std::vector<std::string> noisy;
    for (const auto& r : runs) {
        const std::string id = configId(r.config);
        auto row = [&](const std::string& name, const Stats& st) {
            const bool flag = st.cv > kNoisyCv;
            table.add({id, name, TextTable::number(st.median, 3), TextTable::number(st.min, 3), TextTable::number(st.p90, 3),
                       TextTable::number(100.0 * st.cv, 1) + "%"},
                      flag ? " !" : "");
            if (flag) noisy.push_back(id + " " + name);
        };
        for (const auto& p : r.timing.passes) row(p.name, p.stats);
        row("frame", r.timing.frame.stats);
    }
    table.print();
    for (const auto& r : runs)
        if (clockOf(r) != clock)
            std::printf("note: %s: clock %s (not %s)\n", configId(r.config).c_str(), clockOf(r).c_str(), clock.c_str());
    if (!noisy.empty())
        std::printf("note: ! marks a CV over %.0f%%: the median is uncertain (%zu rows; more --frames or a quieter machine)\n",
                    100 * kNoisyCv, noisy.size());
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
            std::printf("note: %s: %s %s: %s\n", configId(r.config).c_str(), gpu::apiName(r.config.api),
                        r.device.deviceName.c_str(), r.timing.clockNote.c_str());
}

}  // namespace

int runCommand(const std::vector<std::string>& argv) {
    auto parsed = parse(argv);
    if (!parsed) {
        std::cerr << "cavity run: " << parsed.error().message << "\n";
        return exitCode(parsed.error());
    }
    Sweep& s = *parsed;
    if (!s.helpText.empty()) {
        std::cout << s.helpText;
        return 0;
    }
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
    std::vector<gpu::Api> apis;
    for (const auto& b : s.backends) {
        if (b == "gl" || b == "all") apis.push_back(gpu::Api::OpenGL);
        if (b == "vk" || b == "all") apis.push_back(gpu::Api::Vulkan);
    }
    // What runs, in the order it runs: every configuration on each API,
    // those --filter selects. --list prints exactly these ids.
    std::vector<std::pair<gpu::Api, RunConfig>> plan;
    for (auto api : apis)
        for (auto c : *configs) {
            c.api = api;
            if (s.filter && !std::regex_search(configId(c), *s.filter)) continue;
            plan.emplace_back(api, std::move(c));
        }
    if (s.filter && plan.empty()) {
        std::cerr << "cavity run: --filter " << s.filterText << ": matches none of the " << configs->size() * apis.size()
                  << " configurations of this sweep\n";
        return int(ErrorCode::BadInput);
    }
    if (s.list) {
        for (const auto& [api, c] : plan) std::cout << configId(c) << "\n";
        return 0;
    }
    if (auto st = checkWritableDir("--out", s.out); !st) {
        std::cerr << "cavity run: " << st.error().message << "\n";
        return exitCode(st.error());
    }
    std::vector<RunRecord> runs;
    std::vector<RunError> errors;
    int worst = 0;
    std::string command = "cavity run";
    for (const auto& a : argv) command += " " + a;
    s.options.outDir = s.out;
    Progress progress(plan.size(), s.quiet);
    for (auto api : apis) {
        auto backend = gpu::createBackend(api, s.backend);
        if (!backend) {
            progress.interrupt();
            std::cerr << "cavity run: " << backend.error().message << "\n";
            errors.push_back({gpu::apiName(api), exitCode(backend.error()), backend.error().message});
            worst = std::max(worst, exitCode(backend.error()));
            continue;
        }
        auto& gpu = **backend;
        progress.interrupt();
        std::cerr << "cavity run: " << gpu::apiName(api) << ": " << gpu.info().deviceName << " (" << gpu.info().driver
                  << ")\n";
        for (const auto& [planApi, c] : plan) {
            if (planApi != api) continue;
            progress.start(configId(c));
            auto r = runConfig(gpu, c, s.options);
            if (!r) {
                progress.interrupt();
                std::cerr << "cavity run: " << configId(c) << ": " << r.error().message << "\n";
                errors.push_back({gpu::apiName(api), exitCode(r.error()), configId(c) + ": " + r.error().message});
                worst = std::max(worst, exitCode(r.error()));
                continue;
            }
            if (!r->debugMessages.empty() || !r->nonFinite.empty()) progress.interrupt();
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
    progress.interrupt();
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
