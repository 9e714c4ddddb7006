// results.json: what a run measured and on what, in the schema documented in
// harness/measure/results.schema.json (and README.md, "results.json").
#pragma once

#include "measure/namespace.h"
#include "backend.h"
#include "core/config.h"
#include "core/image.h"
#include "measure/roofline.h"
#include "measure/timing.h"

#include <nlohmann/json.hpp>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace cavity::measure {

constexpr const char* kResultsSchema = "cavity.results/1";

struct RunRecord {
    RunConfig config;
    gpu::DeviceInfo device;
    TimingOptions timingOptions;      // what was asked for
    int views = 1;                    // camera views measured in turn (RunOptions::views)
    Timing timing;                    // what was measured
    std::vector<PassSpec> passes;
    std::vector<std::pair<int, int>> passSizes;
    std::vector<kernels::PassShape> passShapes;   // PassChain::passShape, for the floors
    DeviceFloor floorDevice;          // the figures each pass's floor is computed from
    std::map<std::string, gpu::PipelineInfo> pipelines;   // by pass name
    std::map<std::string, std::map<std::string, std::string>> images;   // image -> {"exr": path, "png": path}
    std::vector<std::string> debugMessages;
    // Kept only when RunOptions::keepImages: the user outputs, read back.
    std::map<std::string, HostImage> pixels;
    // With RunOptions::checkDeterminism: the outputs of a second frame were
    // bit-identical to the first.
    bool deterministic = true;
    // PassChain::findNonFinite after the measurement: empty when every float
    // image of every pass is finite.
    std::vector<NonFinite> nonFinite;
};

struct RunError {
    std::string backend;
    int code = 0;
    std::string message;
};

// The clock a configuration was timed on, as a reader needs it: "GPU
// timestamps", "wall clock", or on a software renderer "host timestamps" and
// "host wall clock" (both the CPU's time, not a GPU's).
std::string clockDescription(const RunRecord& r);

nlohmann::json toJson(const Stats& s);
nlohmann::json toJson(const RunRecord& r);
// A pipeline's driver statistics as results.json and a render manifest
// write them ([{executable, name, value}]), and back; a missing or
// malformed list reads as none.
nlohmann::json shaderStatsJson(const std::vector<gpu::ShaderStat>& stats);
std::vector<gpu::ShaderStat> shaderStatsFromJson(const nlohmann::json& list);
nlohmann::json resultsDocument(const std::vector<RunRecord>& runs, const std::vector<RunError>& errors,
                               const std::string& command);

// Atomic: a temporary file renamed into place.
Status writeJson(const std::string& path, const nlohmann::json& doc);

std::string gitCommit();
std::string utcTimestamp();

// A kernel package from disk (--kernels, CAVITY_KERNELS) whose kernel a run
// used: the folder it was loaded from and a digest of its kernel.toml and
// GLSL, so that a verdict or a time is never taken for another version's.
// Longer than any pass or frame (about three hours): a time past it in a
// record (results, render manifests, benchmark JSON) was not measured.
constexpr double kMaxRecordedMs = 1e7;

struct PackageUsed {
    std::string name, folder, digest;
};

// The packages from disk (not built in) that hold one of `kernels`.
std::vector<PackageUsed> packagesUsed(const std::set<std::string>& kernels);
// ... that hold the kernel of one of `configs`.
std::vector<PackageUsed> packagesUsed(const std::vector<RunConfig>& configs);
// Every package loaded from disk: what a record names. A kernel may read a
// parameter another package declares, so the command that runs it again
// loads them all; and every shard of one matrix, whatever kernels it
// holds, names the same packages.
std::vector<PackageUsed> packagesLoaded();
// As results.json, render manifests and gate.json write them:
// [{"name", "folder", "digest"}].
nlohmann::json packagesJson(const std::vector<PackageUsed>& packages);
Result<std::vector<PackageUsed>> parsePackages(const nlohmann::json& j, const std::string& path);
}  // namespace cavity::measure