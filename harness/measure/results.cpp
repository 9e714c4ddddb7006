#include "measure/results.h"
#include "measure/build_version.h"

#include "core/json_file.h"

#include "pipeline/config_id.h"
#include "core/digest.h"
#include "package/package.h"

#include <set>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#ifndef CAVITY_GIT_COMMIT
#define CAVITY_GIT_COMMIT "unknown"
#endif

namespace cavity::measure {

using nlohmann::json;

std::string gitCommit() { return buildCommit(); }

std::string utcTimestamp() {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}

json toJson(const Stats& s) {
    return {{"count", s.count}, {"median_ms", s.median}, {"min_ms", s.min}, {"max_ms", s.max},
            {"mean_ms", s.mean}, {"p90_ms", s.p90}, {"stddev_ms", s.stddev}, {"cv", s.cv}};
}

namespace {

json series(const Series& s) { return {{"stats", toJson(s.stats)}, {"samples_ms", s.ms}}; }

// A number JSON can hold: infinity (too few samples for a noise estimate) is null.
json finite(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json timingJson(const TimingOptions& o, const Timing& t) {
    json warmup = {{"frames", t.warmupFrames}, {"seconds", t.warmupSeconds},
                   {"criterion", t.steadyChecked ? "steady" : "frames"},
                   {"steady", t.steadyChecked ? json(t.steady) : json(nullptr)}};
    return {{"mode", timingModeName(t.mode)},
            {"mode_requested", timingModeName(o.mode)},
            {"batch_frames", t.batchFrames},
            {"warmup", warmup},
            {"min_frames", o.frames},
            {"target_noise", o.maxNoise},
            {"max_seconds", o.maxSeconds},
            {"stop", t.stop},
            {"noise", finite(t.noise)},
            {"seconds", t.seconds},
            {"rejected_frames", t.rejectedFrames},
            {"rejected_note", t.rejectedNote}};
}

json clocksJson(const GpuClockSummary& c) {
    if (c.source.empty()) return nullptr;
    return {{"source", c.source},
            {"device", c.device},
            {"samples", c.samples},
            {"sm_mhz", {{"min", c.smMin}, {"median", c.smMedian}, {"max", c.smMax}}},
            {"mem_mhz", {{"min", c.memMin}, {"median", c.memMedian}, {"max", c.memMax}}},
            {"moved", c.moved()},
            {"event_reasons", c.reasonNames()}};
}

json figureJson(const Figure& f) { return {{"value", f.value}, {"source", f.source}}; }

json launchJson(const std::optional<LaunchFigures>& l) {
    if (!l) return nullptr;
    return {{"fixed_us", l->fixedUs}, {"per_workgroup_ns", l->perWorkgroupNs}};
}

json floorDeviceJson(const DeviceFloor& d) {
    if (!d.figures) return nullptr;
    const DeviceFigures& f = *d.figures;
    return {{"name", f.name},
            {"sm_count", figureJson(f.smCount)},
            {"texture_units_per_sm", figureJson(f.textureUnitsPerSm)},
            {"sm_clock_mhz", figureJson(f.smClockMhz)},
            {"dram_gb_per_s", figureJson(f.dramGBps)},
            {"fetch_slots_per_s", f.slotsPerSecond()},
            {"table_source", f.tableSource},
            {"launch", {{"vk", launchJson(f.launchVk)}, {"gl", launchJson(f.launchGl)}, {"source", f.launchSource}}}};
}

json floorJson(const PassFloorResult& r, double medianMs) {
    if (!r.floor) return nullptr;
    const PassFloor& p = *r.floor;
    return {{"floor_ms", p.ms()},
            {"fetch_floor_ms", p.fetchMs},
            {"dram_floor_ms", p.dramMs},
            {"launch_ms", p.launchMs},
            {"launch_reason", p.launchReason},
            {"bound", p.bound()},
            {"measured_over_floor", medianMs / p.ms()},
            {"pixels", p.pixels},
            {"fetches_per_pixel", p.cost.fetchesPerPixel},
            {"fetch_slots_per_pixel", p.cost.fetchSlotsPerPixel},
            {"bytes_per_pixel", p.cost.bytesPerPixel},
            {"dram_bytes_per_pixel", p.cost.dramBytesPerPixel}};
}

}  // namespace

json shaderStatsJson(const std::vector<gpu::ShaderStat>& stats) {
    json out = json::array();
    for (const auto& s : stats) out.push_back({{"executable", s.executable}, {"name", s.name}, {"value", s.value}});
    return out;
}

std::vector<gpu::ShaderStat> shaderStatsFromJson(const json& list) {
    std::vector<gpu::ShaderStat> stats;
    if (!list.is_array()) return stats;
    for (const auto& s : list) {
        if (!s.is_object() || !s.contains("executable") || !s.contains("name") || !s.contains("value")) continue;
        if (!s["executable"].is_string() || !s["name"].is_string() || !s["value"].is_number()) continue;
        stats.push_back({s["executable"].get<std::string>(), s["name"].get<std::string>(), s["value"].get<double>()});
    }
    return stats;
}

namespace {

json nonFiniteJson(const std::vector<NonFinite>& found) {
    json out = json::array();
    for (const auto& n : found)
        out.push_back({{"pass", n.pass}, {"image", n.image}, {"count", n.count}, {"first", {n.x, n.y}}});
    return out;
}

}  // namespace

json toJson(const RunRecord& r) {
    json params = json::object();
    for (const auto& [k, v] : r.config.params) params[k] = v;
    // Every parameter of every kernel the pipeline ran, defaults included.
    for (const auto& p : r.passes)
        if (const auto* k = kernels::find(p.kernel))
            for (const auto& [name, v] : kernels::withDefaults(*k, r.config.params)) params[name] = v;
    // Where the G-buffer came from; an imported one has no pass in `passes`.
    json gbuffer = {{"source", r.config.gbufferSource()}};
    if (r.config.imported()) gbuffer["file"] = r.config.gbufferFile;
    json passes = json::array();
    for (size_t i = 0; i < r.passes.size() && i < r.timing.passes.size(); ++i) {
        const auto [w, h] = r.passSizes[i];
        const auto shape = i < r.passShapes.size() ? std::optional(r.passShapes[i]) : std::nullopt;
        const PassFloorResult floor =
            passFloor(r.floorDevice, r.passes[i].kernel, r.config.params, double(w) * h, shape, r.config.api);
        const auto pipeline = r.pipelines.find(r.passes[i].name);
        const gpu::PipelineInfo info = pipeline == r.pipelines.end() ? gpu::PipelineInfo{} : pipeline->second;
        passes.push_back({{"name", r.passes[i].name},
                          {"kernel", r.passes[i].kernel},
                          {"width", r.passSizes[i].first},
                          {"height", r.passSizes[i].second},
                          {"shader_path", info.path == gpu::ShaderPath::Spirv ? "spirv" : "glsl-fallback"},
                          {"shader_stats", shaderStatsJson(info.stats)},
                          {"shader_stats_reason", info.statsReason},
                          {"stats", toJson(r.timing.passes[i].stats)},
                          {"samples_ms", r.timing.passes[i].ms},
                          {"floor", floorJson(floor, r.timing.passes[i].stats.median)},
                          {"floor_reason", floor.reason}});
    }
    return {
        {"id", configId(r.config)},
        {"backend", gpu::apiName(r.config.api)},
        {"device",
         {{"name", r.device.deviceName}, {"driver", r.device.driver}, {"api_version", r.device.apiVersion},
          {"vendor", r.device.vendor}, {"software_renderer", r.device.softwareRenderer}, {"uuid", r.device.uuid}}},
        {"config",
         {{"scene", r.config.imported() ? importStem(r.config.gbufferFile) : r.config.scene()},
          {"gbuffer", gbuffer},
          {"kernel", r.config.kernel}, {"samples", r.config.samples()},
          {"blur", r.config.blur()}, {"width", r.config.width}, {"height", r.config.height},
          {"resolution", r.config.half ? "half" : "full"},
          {"stage", r.config.stage == gpu::Stage::Compute ? "compute" : "fragment"},
          {"api", gpu::apiName(r.config.api)}, {"params", params}}},
        {"frames", {{"warmup", r.timing.warmupFrames}, {"measured", int(r.timing.frame.ms.size())}}},
        {"timing", [&] {
             json t = timingJson(r.timingOptions, r.timing);
             t["views"] = r.views;
             return t;
         }()},
        {"gpu_clocks", clocksJson(r.timing.clocks)},
        {"floor_device", floorDeviceJson(r.floorDevice)},
        {"floor_device_reason", r.floorDevice.reason},
        {"clock", r.timing.clock},
        {"clock_note", r.timing.clockNote},
        {"passes", passes},
        {"frame", series(r.timing.frame)},
        {"pipeline", series(r.timing.pipeline)},
        {"frame_wall", series(r.timing.frameWall)},
        {"frame_gpu_timestamps", series(r.timing.frameGpu)},
        {"images", r.images},
        {"debug_messages", r.debugMessages},
        {"non_finite", nonFiniteJson(r.nonFinite)},
    };
}

std::string clockDescription(const RunRecord& r) {
    const std::string host = r.device.softwareRenderer ? "host " : "";
    if (r.timing.clock == "gpu-timestamp") return r.device.softwareRenderer ? "host timestamps" : "GPU timestamps";
    if (r.timing.clock == "wall") return host + "wall clock";
    return host + r.timing.clock;
}

json resultsDocument(const std::vector<RunRecord>& runs, const std::vector<RunError>& errors,
                     const std::string& command) {
    json doc = {{"schema", kResultsSchema},
                {"git_commit", gitCommit()},
                {"created_utc", utcTimestamp()},
                {"command", command},
                {"runs", json::array()},
                {"errors", json::array()}};
    for (const auto& r : runs) doc["runs"].push_back(toJson(r));
    for (const auto& e : errors) doc["errors"].push_back({{"backend", e.backend}, {"code", e.code}, {"message", e.message}});
    return doc;
}

Status writeJson(const std::string& path, const json& doc) { return writeFileAtomically(path, core::jsonText(doc, 2) + "\n"); }

std::vector<PackageUsed> packagesUsed(const std::set<std::string>& kernels) {
    std::vector<PackageUsed> out;
    for (const auto& p : kernels::packages()) {
        if (p.builtIn || !kernels.count(p.name)) continue;
        std::ifstream toml(std::filesystem::path(p.folder) / "kernel.toml", std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(toml)), std::istreambuf_iterator<char>());
        for (const auto& key : p.sourceKeys)
            if (const auto* src = kernels::packageSource(key)) text += "\n" + key + "\n" + src->text;
        out.push_back({p.name, std::filesystem::absolute(p.folder).lexically_normal().string(),
                       core::digestText(core::fnv1a64(text.data(), text.size()))});
    }
    return out;
}

std::vector<PackageUsed> packagesLoaded() {
    std::set<std::string> all;
    for (const auto& p : kernels::packages())
        if (!p.builtIn) all.insert(p.name);
    return packagesUsed(all);
}

std::vector<PackageUsed> packagesUsed(const std::vector<RunConfig>& configs) {
    std::set<std::string> kernels;
    for (const auto& c : configs) kernels.insert(c.kernel);
    return packagesUsed(kernels);
}

nlohmann::json packagesJson(const std::vector<PackageUsed>& packages) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& p : packages) out.push_back({{"name", p.name}, {"folder", p.folder}, {"digest", p.digest}});
    return out;
}

Result<std::vector<PackageUsed>> parsePackages(const nlohmann::json& j, const std::string& path) {
    std::vector<PackageUsed> out;
    if (!j.is_array()) return badInput(path + ": kernel_packages must be a list");
    for (const auto& p : j) {
        if (!p.is_object() || !p.contains("name") || !p.contains("folder") || !p.contains("digest") || !p["name"].is_string() ||
            !p["folder"].is_string() || !p["digest"].is_string())
            return badInput(path + ": kernel_packages: each entry must have string name, folder and digest");
        out.push_back({p["name"], p["folder"], p["digest"]});
    }
    return out;
}

}  // namespace cavity::measure