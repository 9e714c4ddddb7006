#include "render_command.h"
#include "core/shell_words.h"

#include "kernel.h"

#include "values.h"
#include "flags.h"
#include "gate/gate_judge.h"
#include "render/render_folder.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "shard_sources.h"

#include <mutex>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <future>
#include <thread>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>

namespace cavity::render {

namespace fs = std::filesystem;

namespace {

// The flags of cavity_render, declared once: --help and the parse read this.
const flags::CommandSpec& renderSpec() {
    static const flags::CommandSpec spec{
        "cavity_render",
        "Renders a matrix of DIR/matrices.json (default: the repository's baselines/) into a render folder for `cavity gate judge`, "
        "on the GPU machine (no OpenImageIO). `cavity_render quality [the flags of cavity quality]` measures "
        "quality there (see cavity_render quality --help).",
        {
            {"--matrix", "NAME", "the matrix of matrices.json to render (required)"},
            {"--out", "DIR", "the render folder to write (required)"},
            {"--baselines", "DIR", "folder holding matrices.json (default: baselines/ of the first folder from the working directory up that holds baselines/matrices.json, else of the source tree this binary was built from)"},
            {"--backend", "gl|vk|all", "backends to render on (default all)"},
            {"--shard", "I/N", "shard I of N (0 <= I < N); also GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS, TEST_SHARD_INDEX"},
            {"--device", "K", "device index (0..64; default 0)"},
            {"--filter", "REGEX", "only the configurations whose id matches (searched)"},
            {"--list", "", "print the ids of the selection (with --backend and --shard), one a line, and render nothing"},
            {"--repeat", "N", "renders of each configuration (1..1000; default 1)"},
            {"--validation", "", "enable the Vulkan validation layers and the GL debug output"},
            {"--timing", "batch|drained", "batch: back-to-back frames; drained: wait for the GPU after each (default: the device's)"},
            {"--max-noise", "PCT", "stop measuring once the median's noise is under PCT percent (0..100)"},
            {"--max-time", "S", "stop measuring after S seconds (0.001..3600)"},
            {"--views", "N", "camera views measured in turn, as cavity_bench measures (1..4; default 1)"},
            {"--kernel-source", "NAME=FILE", "render with kernels/NAME replaced by FILE's text (a planted defect); repeatable",
             "Options", true},
            {"--store", "DIR|URL",
             "judge here: an image whose digest is not approved is compared, with the gate's tolerances "
             "(<baselines>/manifest.json), with the nearest image approved for the device's class, fetched from this "
             "image store; only the images that fail (or have no reference of the class) are written, the others "
             "travel as verdicts and metrics (docs/store.md)"},
            flags::storeCacheFlag(),
        },
        "",
        "",
        "\nExit codes: 0 every configuration rendered, 1 a pass wrote NaN or infinity (the folder is written), 2 bad "
        "input (nothing written; where it is a configuration's own, a kernel that does not compile, the folder is "
        "written and its manifest names it), 3 a backend did not start, 4 a configuration failed on the GPU; with --store, 5 "
        "the image store cannot be reached or refuses, 6 a stored object does not have its digest (docs/store.md).",
        {
            "cavity_render --matrix gpu --out out/render",
            "cavity_render --matrix ci --backend vk --kernel-source ssao_alchemy.glsl=my_alchemy.glsl --out out/edit",
            "cavity_render --matrix gpu --store references/ --out out/render",
            "cavity_render quality --kernel alchemy_fast --res 1920x1080",
        },
    };
    return spec;
}

int fail(const Error& e) {
    std::cerr << "cavity_render: " << flags::printable(e.message) << "\n";
    return flags::exitCode(e);
}

// The command that renders this again: the packages main loaded (--kernels
// or CAVITY_KERNELS) first, as `cavity run` records them.
std::string joined(const std::vector<measure::PackageUsed>& packages, const std::vector<std::string>& argv) {
    std::vector<std::string> args;
    for (const auto& p : packages) args.insert(args.end(), {"--kernels", p.folder});
    args.insert(args.end(), argv.begin(), argv.end());
    return core::commandLine("cavity_render", args);
}

// The gate's precedence (gate::GateRun::exitCode): bad input, then a
// backend that did not start, then a GPU error, then a pass that wrote NaN
// or infinity (1, as in every tool: the run finished, the image is wrong).
int worst(const RenderManifest& m) {
    bool bad = false, backend = !m.backendErrors.empty(), gpuError = false, nonFinite = false;
    for (const auto& c : m.configs)
        for (const auto& r : c.renders) {
            bad |= r.errorCode == int(ErrorCode::BadInput);
            backend |= r.errorCode == int(ErrorCode::BackendUnavailable);
            nonFinite |= r.errorCode == int(ErrorCode::CheckFailed);
            gpuError |= r.errorCode != 0 && r.errorCode != int(ErrorCode::CheckFailed);
        }
    return bad ? 2 : backend ? 3 : gpuError ? 4 : nonFinite ? 1 : 0;
}

struct JudgedHere {
    std::atomic<int> passed{0}, failed{0}, unjudged{0};
    std::mutex mutex;
    int storeCode = 0;                    // the first store failure (5, 6): the exit code
};

// --store: the gate's own judging of each image that is not approved by
// digest, against its class's approved image from the store; the verdict
// and metrics go into the manifest (Rendering::judged), and the folder
// writer keeps the files of those that failed.
Status judgeHere(Rendering& r, const gate::Judge& judge, JudgedHere& tally) {
    CAVITY_ASSIGN(const gate::ConfigResult res, gate::judgeRendering(r, judge));
    // The store failed for this configuration: its images are written
    // unjudged, and the run ends with the store's exit code, as the gate's.
    if (!res.error.empty()) {
        tally.unjudged += int(r.images.size());
        std::lock_guard<std::mutex> lock(tally.mutex);
        std::fprintf(stderr, "cavity_render: %s: not judged here: %s\n", r.id.c_str(), res.error.c_str());
        if (tally.storeCode == 0) tally.storeCode = res.errorCode;
        return {};
    }
    for (const auto& check : res.images) {
        // Approved by digest: decided, no file. Known bad: failed, written.
        // Anything else not judged by tolerance here is left to the judge.
        if (check.route == "digest") ++tally.passed;
        else if (check.route == "negative") ++tally.failed;
        else if (check.route != "tolerance") ++tally.unjudged;
        if (check.route != "tolerance") continue;
        RemoteCheck k;
        k.reference = check.reference;
        k.referenceDigest = check.referenceDigest;
        k.passed = check.passed();
        k.failures = check.failures;
        k.metrics = check.metrics ? gate::metricsJson(*check.metrics) : nlohmann::json::object();
        k.tolerance = gate::toleranceJson(check.tolerance);
        (k.passed ? tally.passed : tally.failed) += 1;
        r.judged[check.image] = std::move(k);
    }
    return {};
}

// --store: each rendering is judged on a thread of its own while the GPU
// renders the next (the metrics of three 1920x1080 images take longer than
// rendering them), at most one per core in flight; the writer gets them in
// the order they were rendered.
class JudgingQueue {
public:
    JudgingQueue(const gate::Judge* judge, JudgedHere& tally, std::function<Status(Rendering&&)> write)
        : judge_(judge), tally_(tally), write_(std::move(write)),
          limit_(std::max<size_t>(1, std::thread::hardware_concurrency())) {}

    Status push(Rendering&& r) {
        if (!judge_) return write_(std::move(r));
        pending_.push_back(std::async(std::launch::async, [this, r = std::move(r)]() mutable -> Result<Rendering> {
            if (r.error.empty()) CAVITY_TRY(judgeHere(r, *judge_, tally_));
            return std::move(r);
        }));
        while (pending_.size() > limit_ ||
               (!pending_.empty() && pending_.front().wait_for(std::chrono::seconds(0)) == std::future_status::ready))
            CAVITY_TRY(popFront());
        return {};
    }

    Status drain() {
        while (!pending_.empty()) CAVITY_TRY(popFront());
        return {};
    }

private:
    Status popFront() {
        auto done = pending_.front().get();
        pending_.pop_front();
        if (!done) return done.error();
        return write_(std::move(*done));
    }

    const gate::Judge* judge_;
    JudgedHere& tally_;
    std::function<Status(Rendering&&)> write_;
    size_t limit_;
    std::deque<std::future<Result<Rendering>>> pending_;
};

}  // namespace

Result<RenderCommand> parseRenderFlags(const std::vector<std::string>& argv) {
    std::optional<std::string> shardFlag;
    RenderCommand o;
    CAVITY_ASSIGN(const flags::ParsedFlags parsed, flags::parseFlags(renderSpec(), argv));
    o.help = parsed.help;
    if (parsed.help) {
        o.helpText = parsed.helpText;
        return o;
    }
    o.render.validation = parsed.has("--validation");
    o.list = parsed.has("--list");
    for (const auto& [flag, v] : parsed.values) {
        if (flag == "--matrix") o.matrix = v;
        else if (flag == "--baselines") o.baselines = v;
        else if (flag == "--out") o.out = v;
        else if (flag == "--filter") o.filter = v;
        else if (flag == "--backend") {
            if (v == "gl") o.render.apis = {gpu::Api::OpenGL};
            else if (v == "vk") o.render.apis = {gpu::Api::Vulkan};
            else if (v == "all") o.render.apis = {gpu::Api::OpenGL, gpu::Api::Vulkan};
            else return badInput("--backend " + v + ": must be gl, vk or all");
        } else if (flag == "--shard") {
            shardFlag = v;
        } else if (flag == "--device") {
            CAVITY_ASSIGN(o.render.device, flags::parseInt(flag, v, 0, 64));
        } else if (flag == "--repeat") {
            CAVITY_ASSIGN(o.render.repeat, flags::parseInt(flag, v, 1, 1000));
        } else if (flag == "--kernel-source") {
            // NAME=FILE: render with kernels/NAME replaced by FILE's text, so a
            // planted defect can be rendered on a machine without a build.
            CAVITY_TRY(flags::addKernelSource(v, o.render.overrides, o.replaced));
        } else if (flag == "--timing") {
            if (v != "batch" && v != "drained") return badInput("--timing " + v + ": must be batch or drained");
            o.render.mode = v == "batch" ? TimingMode::Batch : TimingMode::Drained;
        } else if (flag == "--max-noise") {
            CAVITY_ASSIGN(const double pct, flags::parseNumber(flag, v, 0, 100));
            o.render.maxNoise = pct / 100;
        } else if (flag == "--max-time") {
            CAVITY_ASSIGN(o.render.maxSeconds, flags::parseNumber(flag, v, 0.001, 3600));
        } else if (flag == "--views") {
            CAVITY_ASSIGN(o.render.views, flags::parseInt(flag, v, 1, 4));
        } else if (flag == "--store") {
            if (!o.store) o.store.emplace();
            o.store->location = v;
        } else if (flag == "--store-cache") {
            if (!o.store) o.store.emplace();
            o.store->cache = v;
        }
    }
    // As cavity's commands find them: from the working directory up, else the
    // source tree this binary was built from (flags::defaultBaselines).
    if (o.baselines.empty()) {
        CAVITY_ASSIGN(o.baselines, flags::defaultBaselines());
    }
    if (o.matrix.empty()) return badInput("--matrix: missing (name a matrix of " + o.baselines + "/matrices.json)");
    if (o.out.empty() && !o.list) return badInput("--out: missing (the render folder to write)");
    // --shard, GoogleTest's and Bazel's variables: one partition (shard_sources.h).
    CAVITY_ASSIGN(const flags::Shard shard, flags::resolveShard(shardFlag));
    o.shardIndex = shard.index;
    o.shardCount = shard.count;
    CAVITY_TRY(flags::touchShardStatusFiles());
    return o;
}

int renderCommand(const std::vector<std::string>& argv) {
    const auto start = std::chrono::steady_clock::now();
    auto o = parseRenderFlags(argv);
    if (!o) return fail(o.error());
    if (o->help) {
        std::cout << o->helpText;
        return 0;
    }
    auto matrix = plan::loadMatrix((fs::path(o->baselines) / "matrices.json").string(), o->matrix);
    if (!matrix) return fail(matrix.error());
    auto entries = plan::selectEntries(*matrix, o->shardIndex, o->shardCount, o->filter);
    if (!entries) return fail(entries.error());
    std::vector<RunConfig> selected;
    for (const auto& e : *entries) selected.push_back(e.config);
    if (auto st = checkSourcesUsed(o->replaced, selected); !st) return fail(st.error());
    if (o->list) {
        for (const auto& c : selected)
            if (std::find(o->render.apis.begin(), o->render.apis.end(), c.api) != o->render.apis.end())
                std::cout << configId(c) << "\n";
        return 0;
    }
    if (auto env = gpu::withEnvironment({}); !env) return fail(env.error());
    if (auto st = checkWritableDir("--out", o->out); !st) return fail(st.error());

    RenderManifest header;
    header.matrix = matrix->name;
    header.matrixHash = matrix->hash;
    header.gitCommit = gitCommit();
    header.createdUtc = utcTimestamp();
    header.packages = measure::packagesLoaded();
    header.command = joined(header.packages, argv);
    header.shardIndex = o->shardIndex;
    header.shardCount = o->shardCount;
    header.filter = o->filter;
    header.repeat = o->render.repeat;
    header.replaced = o->replaced;
    // Images approved by digest for this device are not written: a clean
    // render of a known device sends back its manifest alone.
    auto approvals = plan::loadApprovals((fs::path(o->baselines) / "approvals.json").string());
    if (!approvals) return fail(approvals.error());
    std::optional<gate::Judge> judge;
    if (o->store) {
        if (o->store->location.empty() && !o->store->cache.empty())
            return fail(badInput("--store-cache: needs --store (the image store to judge against)"));
        auto j = gate::prepareJudge(o->baselines, selected, o->out, *o->store, true);
        if (!j) return fail(j.error());
        judge = std::move(*j);
    }
    FolderWriter writer(o->out, header, std::move(*approvals));
    if (auto st = writer.begin(); !st) return fail(st.error());
    JudgedHere tally;
    JudgingQueue queue(judge ? &*judge : nullptr, tally, [&](Rendering&& r) -> Status {
        const std::string what = r.id + (r.repetition ? " (repetition " + std::to_string(r.repetition) + ")" : "");
        const std::string error = r.error;
        const uint64_t before = writer.bytesWritten();
        CAVITY_TRY(writer.add(std::move(r)));
        if (!error.empty()) std::fprintf(stderr, "render: %-60s error: %s\n", what.c_str(), error.c_str());
        else std::fprintf(stderr, "render: %-60s %8.1f KiB\n", what.c_str(), double(writer.bytesWritten() - before) / 1024.0);
        return {};
    });
    std::vector<BackendFailure> failures;
    auto sink = [&](Rendering&& r) -> Status { return queue.push(std::move(r)); };
    if (auto st = renderEntries(*matrix, *entries, o->render, sink, &failures); !st) return fail(st.error());
    if (auto st = queue.drain(); !st) return fail(st.error());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (auto st = writer.finish(failures, seconds); !st) return fail(st.error());
    for (const auto& f : failures) std::cerr << "cavity_render: " << gpu::apiName(f.api) << ": " << f.message << "\n";
    if (judge)
        std::printf("judged here against the device class's approved images: %d passed (no file), %d failed (written); "
                    "%d not judged here (no reference of the class, or the store failed: written, for cavity gate judge)\n",
                    tally.passed.load(), tally.failed.load(), tally.unjudged.load());
    std::printf("wrote %s: %zu configurations x %d repetitions of matrix %s, %d image files, %.1f MiB, %.1f s\n",
                (fs::path(o->out) / "manifest.json").c_str(), writer.manifest().configs.size(), o->render.repeat,
                matrix->name.c_str(), writer.filesWritten(), double(writer.bytesWritten()) / (1024.0 * 1024.0), seconds);
    const int code = worst(writer.manifest());
    if (code == 0 && tally.storeCode != 0) return tally.storeCode;
    return code;
}

}  // namespace cavity::render
