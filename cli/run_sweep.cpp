#include "run_sweep.h"

#include "kernel.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "plan/axes.h"

#include <algorithm>
#include <set>

namespace cavity::cli {

// The flags of cavity run, declared once: --help, the parse and the README's
// flag table (tests/readme_flags.py checks it against --help) read this.
const CommandSpec& runSpec() {
    static const CommandSpec spec = [] {
        CommandSpec c;
        c.program = "cavity run";
        c.description =
            "Runs a sweep of kernel configurations on one or both backends: images under --out/<id>/, "
            "results.json, table.txt (every pass, its clock) and index.html (every image, a chart per kernel); "
            "a summary per kernel on stdout, progress on stderr. Every list flag takes "
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
            {"--kernel-source", "NAME=FILE",
             "run with kernels/NAME replaced by FILE's text (an edited kernel; NAME a path under kernels/ or a file "
             "name one source has); repeatable; a configuration of the run must compile NAME", sweep, true},
            {"--frames", "N", "measured frames, at least (1..100000; default 50)", timing},
            {"--warmup", "N", "warm-up frames, at least (0..10000; default 5)", timing},
            {"--timing", "batch|drained", "batch: back-to-back frames; drained: wait for the GPU after each (default: the device's)", timing},
            {"--max-noise", "PCT", "stop measuring once the median's noise is under PCT percent (0..100; 0: a fixed count)", timing},
            {"--max-time", "S", "stop measuring after S seconds (0.001..3600)", timing},
            {"--views", "N", "camera views measured in turn, frame f on view f mod N, as cavity_bench measures (1..4; "
                             "default 1: every frame on one chain); the images are view 0's", timing},
            {"--device", "K", "device index (0..64; default 0)", output},
            {"--validation", "", "enable the Vulkan validation layers and the GL debug output", output},
            {"--out", "DIR", "output folder (default out)", output},
            {"--list", "", "print the configuration ids this run would measure, one a line, and run nothing", output},
            {"--quiet", "", "no progress or device lines on stderr: errors alone", output},
            {"--table", "", "print table.txt's table (every pass of every configuration) before the summary", output},
        };
        for (auto& f : kernelParamFlags({"scene"})) c.flags.push_back(std::move(f));
        c.footer = "\n" + kernelHelp() +
                   "\nIds read scene/kernel/nSAMPLES/bBLUR[/param=value..]/full|half/WxH/api/stage "
                   "(docs/benchmarking.md, \"Configuration ids\"). Exit codes: 0 ok, 1 NaN written, 2 bad usage, 3 no backend, "
                   "4 GPU error.";
        c.examples = {
            "cavity run --kernel alchemy_fast --backend gl,vk --res 1920x1080",
            "cavity run --kernel alchemy,hemisphere_fast --samples 8,16,32 --resolution full,half",
            "cavity run --scene slats --blur 0,4 --list",
        };
        return c;
    }();
    return spec;
}

namespace {

// A comma list whose every item must be one of `allowed`.
Result<std::vector<std::string>> choiceList(const std::string& flag, const std::string& v,
                                            const std::vector<std::string>& allowed, const std::string& what) {
    CAVITY_ASSIGN(auto items, splitList(flag, v));
    for (const auto& item : items)
        if (std::find(allowed.begin(), allowed.end(), item) == allowed.end())
            return badInput(flag + " " + item + ": must be " + what);
    return items;
}

// The Sweep group: which configurations. True when the flag was one of them.
Result<bool> sweepFlag(Sweep& s, const std::string& flag, const std::string& v) {
    if (flag == "--backend") {
        CAVITY_ASSIGN(s.backends, choiceList(flag, v, {"gl", "vk", "all"}, "gl, vk or all"));
        // all and a backend it holds would run that backend's configurations twice under one id.
        if (s.backends.size() > 1 && std::find(s.backends.begin(), s.backends.end(), "all") != s.backends.end())
            return badInput(flag + " '" + v + "': all is gl and vk; give it alone");
    } else if (flag == "--kernel") {
        CAVITY_ASSIGN(s.kernels, splitList(flag, v));
    } else if (flag == "--scene") {
        CAVITY_ASSIGN(s.scenes, splitList(flag, v));
        s.sceneGiven = true;
    } else if (flag == "--resolution") {
        CAVITY_ASSIGN(s.resolutions, choiceList(flag, v, {"full", "half"}, "full or half"));
    } else if (flag == "--res") {
        s.sizeGiven = true;
        s.sizes.clear();
        CAVITY_ASSIGN(const auto items, splitList(flag, v));
        for (const auto& r : items) {
            CAVITY_ASSIGN(auto wh, parseResolution("--res", r));
            if (std::find(s.sizes.begin(), s.sizes.end(), wh) != s.sizes.end())
                return badInput(flag + " '" + v + "': " + r + " is a size given twice");
            s.sizes.push_back(wh);
        }
    } else if (flag == "--gbuffer") {
        CAVITY_ASSIGN(s.gbuffers, choiceList(flag, v, {"sdf", "raster", "import"}, "sdf, raster or import"));
    } else if (flag == "--gbuffer-file") {
        s.gbufferFile = v;
    } else if (flag == "--stage") {
        CAVITY_ASSIGN(const auto items, choiceList(flag, v, {"compute", "fragment"}, "compute or fragment"));
        s.stages.clear();
        for (const auto& st : items) s.stages.push_back(st == "compute" ? gpu::Stage::Compute : gpu::Stage::Fragment);
    } else if (flag == "--filter") {
        CAVITY_ASSIGN(s.filter, parseFilter(flag, v));
        s.filterText = v;
    } else if (flag == "--kernel-source") {
        CAVITY_TRY(addKernelSource(v, s.options.overrides, s.replaced));
    } else {
        return false;
    }
    return true;
}

// The Timing and Device and output groups.
Status runFlag(Sweep& s, const std::string& flag, const std::string& v) {
    if (flag == "--frames") {
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
    } else if (flag == "--views") {
        CAVITY_ASSIGN(s.options.views, parseInt(flag, v, 1, 4));
    } else if (flag == "--device") {
        CAVITY_ASSIGN(s.backend.deviceIndex, parseInt(flag, v, 0, 64));
    } else if (flag == "--out") {
        s.out = v;
    }
    return {};
}

// Every kernel parameter sweeps: --radius 0.5,1.0 is two configurations.
// Each value is parsed and checked once, here (kernels/params.h).
Result<std::vector<double>> paramValues(const std::string& flag, const std::string& v) {
    CAVITY_ASSIGN(auto items, splitList(flag, v));
    const auto& decl = *kernels::findParam(flag.substr(2));
    std::vector<double> values;
    for (const auto& item : items) {
        CAVITY_ASSIGN(double x, kernels::parseValue(decl, item));
        if (std::find(values.begin(), values.end(), x) != values.end()) {
            const std::string shader = kernels::valueText(decl, x);
            return badInput(flag + " '" + v + "': " + item + " is a value given twice" +
                            (shader == item ? "" : " (the shader's 32-bit float of it is " + shader + ")"));
        }
        values.push_back(x);
    }
    return values;
}

// What no single flag can check: --gbuffer import and its capture, and a
// scene given where the capture is the scene.
Status checkGBufferFlags(const Sweep& s) {
    const bool import = std::find(s.gbuffers.begin(), s.gbuffers.end(), "import") != s.gbuffers.end();
    if (import && s.gbufferFile.empty())
        return badInput("--gbuffer import: needs --gbuffer-file FILE (a multi-channel OpenEXR capture)");
    if (!import && !s.gbufferFile.empty())
        return badInput("--gbuffer-file " + s.gbufferFile + ": only used with --gbuffer import");
    const bool onlyImport =
        std::all_of(s.gbuffers.begin(), s.gbuffers.end(), [](const std::string& g) { return g == "import"; });
    if (onlyImport && s.sceneGiven)
        return badInput("--scene " + s.scenes[0] + ": not used with --gbuffer import (the capture is the scene)");
    return {};
}

}  // namespace

Result<Sweep> parseSweep(const std::vector<std::string>& argv) {
    Sweep s;
    CAVITY_ASSIGN(const ParsedFlags parsed, parseFlags(runSpec(), argv));
    if (parsed.help) {
        s.helpText = parsed.helpText;
        return s;
    }
    s.backend.validation = parsed.has("--validation");
    s.list = parsed.has("--list");
    s.quiet = parsed.has("--quiet");
    s.table = parsed.has("--table");
    for (const auto& [flag, v] : parsed.values) {
        CAVITY_ASSIGN(const bool done, sweepFlag(s, flag, v));
        if (done) continue;
        if (isKernelParam(flag.substr(2))) {
            CAVITY_ASSIGN(s.params[flag.substr(2)], paramValues(flag, v));
            continue;
        }
        CAVITY_TRY(runFlag(s, flag, v));
    }
    CAVITY_TRY(checkGBufferFlags(s));
    return s;
}

Result<std::vector<RunConfig>> expandSweep(const Sweep& s) {
    plan::Axes axes;
    axes.scenes = s.scenes;
    axes.kernels = s.kernels;
    axes.params.assign(s.params.begin(), s.params.end());
    for (const auto& r : s.resolutions) axes.half.push_back(r == "half");
    axes.sizes = s.sizes;
    axes.stages = s.stages;
    axes.gbuffers = s.gbuffers;
    axes.gbufferFile = s.gbufferFile;
    // A sweep skips the combinations a kernel lacks (SSDO at half
    // resolution); asked for alone, they are an error.
    const bool alone = s.kernels.size() == 1 && s.resolutions.size() == 1;
    std::vector<RunConfig> out;
    CAVITY_TRY(plan::forEachConfig(axes, s.base, [&](RunConfig c) -> Status {
        if (c.imported()) {
            // The capture is the scene: one configuration, whatever --scene says.
            if (c.scene() != s.scenes.front()) return {};
            c.params.erase("scene");
        }
        if (c.half && !supportsHalf(c.kernel) && !alone) return {};
        CAVITY_TRY(validate(c));
        out.push_back(std::move(c));
        return {};
    }));
    // A parameter that no pass of any configuration reads changes nothing
    // that runs, and would only add a segment to the ids: another kernel's
    // own parameter given for this one, most likely.
    for (const auto& [name, values] : s.params) {
        const auto reads = [&name](const RunConfig& c) { return pipeline::pipelineReads(c, name); };
        if (out.empty() || std::any_of(out.begin(), out.end(), reads)) continue;
        // What would read it: the selection at half resolution (the fused
        // tail), else the AO kernels whose pipelines do, to name.
        if (std::any_of(out.begin(), out.end(), [&](RunConfig c) {
                c.half = true;
                return supportsHalf(c.kernel) && reads(c);
            }))
            return badInput("--" + name + ": read at half resolution only; add --resolution half");
        std::string owners;
        size_t count = 0;
        for (const auto& k : kernels::all()) {
            RunConfig other = out.front();
            other.kernel = k.name;
            if (k.role == kernels::Role::Ao && reads(other)) owners += (count++ ? ", " : "") + k.name;
        }
        return badInput("--" + name + ": no kernel of the selection reads it" +
                        (count ? " (" + owners + (count == 1 ? " does)" : " do)") : std::string()));
    }
    // A mixed selection: each configuration keeps the parameters its own
    // pipeline reads, and those that then coincide run once.
    std::vector<std::string> names;
    for (const auto& p : s.params) names.push_back(p.first);
    std::vector<RunConfig> kept;
    std::set<std::string> seen;
    for (auto& c : out) {
        pipeline::dropUnreadParams(c, names);
        if (seen.insert(pipeline::configId(c)).second) kept.push_back(std::move(c));
    }
    return kept;
}

}  // namespace cavity::cli
