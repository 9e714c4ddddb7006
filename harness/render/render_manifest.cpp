#include "render/render_manifest.h"

#include "core/json_input.h"
#include "kernel.h"
#include "measure/results.h"

#include <cmath>

namespace cavity::render {

using nlohmann::json;

namespace {

json toJson(const gpu::DeviceInfo& d) {
    return {{"name", d.deviceName}, {"driver", d.driver}, {"api_version", d.apiVersion}, {"vendor", d.vendor},
            {"software_renderer", d.softwareRenderer}, {"uuid", d.uuid}};
}

json toJson(const RenderEntry& r) {
    json timings = json::array(), images = json::array();
    auto orNull = [](double x) { return std::isfinite(x) ? json(x) : json(); };
    for (const auto& t : r.timings) {
        const double registers = gpu::registerCount(t.shaderStats);
        timings.push_back({{"pass", t.pass}, {"median_ms", t.medianMs}, {"clock", t.clock}, {"ci_low_ms", orNull(t.lowMs)},
                           {"ci_high_ms", orNull(t.highMs)}, {"registers", registers >= 0 ? json(registers) : json()},
                           {"shader_stats", measure::shaderStatsJson(t.shaderStats)}});
    }
    for (const auto& i : r.images) {
        images.push_back({{"name", i.name}, {"file", i.file.empty() ? json(nullptr) : json(i.file)},
                          {"width", i.stored.width}, {"height", i.stored.height}, {"channels", i.stored.channels},
                          {"digest", i.stored.digest}, {"bytes", i.stored.bytes}});
        if (const auto& k = i.judged)
            images.back()["judged"] = {{"reference", k->reference}, {"reference_digest", k->referenceDigest},
                                       {"passed", k->passed}, {"failures", k->failures}, {"metrics", k->metrics},
                                       {"tolerance", k->tolerance}};
    }
    return {{"repetition", r.repetition}, {"error", r.error}, {"error_code", r.errorCode},
            {"deterministic", r.deterministic}, {"timings", timings}, {"images", images}};
}

// The manifest's parts, each field read for its type and range
// (core/json_input.h): a manifest is a file a user can damage or edit.
using core::JsonObject;
constexpr int kMaxSide = 16384;            // an image side: the largest texture the backends make
constexpr double kMaxBytes = 9007199254740992.0;   // 2^53: a file size a double holds exactly

// One timing of a manifest; the interval and the statistics are absent from
// older ones.
Result<PassTime> readPassTime(const JsonObject& t) {
    PassTime p;
    CAVITY_ASSIGN(p.pass, t.str("pass"));
    if (p.pass.empty()) return t.bad("pass", "must name a pass");
    CAVITY_ASSIGN(p.medianMs, t.number("median_ms", 0, measure::kMaxRecordedMs));
    CAVITY_ASSIGN(p.clock, t.str("clock"));
    if (p.clock != "gpu-timestamp" && p.clock != "wall") return t.bad("clock", "must be gpu-timestamp or wall");
    auto optional = [&](const char* key) -> Result<double> {
        if (!t.has(key)) return NAN;
        CAVITY_ASSIGN(const auto v, t.numberOrNull(key, 0, measure::kMaxRecordedMs));
        return v ? *v : NAN;
    };
    CAVITY_ASSIGN(p.lowMs, optional("ci_low_ms"));
    CAVITY_ASSIGN(p.highMs, optional("ci_high_ms"));
    p.shaderStats = measure::shaderStatsFromJson(t.has("shader_stats") ? t.raw().at("shader_stats") : json());
    return p;
}

Result<ImageEntry> readImage(const JsonObject& ij) {
    ImageEntry i;
    CAVITY_ASSIGN(i.name, ij.str("name"));
    if (!ij.has("file")) return ij.bad("file", "missing (a file name, or null)");
    if (!ij.raw().at("file").is_null()) {
        CAVITY_ASSIGN(i.file, ij.str("file"));
    }
    CAVITY_ASSIGN(i.stored.width, ij.integer("width", 1, kMaxSide));
    CAVITY_ASSIGN(i.stored.height, ij.integer("height", 1, kMaxSide));
    CAVITY_ASSIGN(i.stored.channels, ij.integer("channels", 1, 4));
    CAVITY_ASSIGN(i.stored.digest, ij.str("digest"));
    CAVITY_ASSIGN(const double bytes, ij.number("bytes", 0, kMaxBytes));
    if (bytes != std::floor(bytes)) return ij.bad("bytes", "must be a whole number of bytes");
    i.stored.bytes = uint64_t(bytes);
    if (ij.has("judged")) {
        CAVITY_ASSIGN(const JsonObject k, ij.object("judged"));
        RemoteCheck c;
        CAVITY_ASSIGN(c.reference, k.str("reference"));
        CAVITY_ASSIGN(c.referenceDigest, k.str("reference_digest"));
        CAVITY_ASSIGN(c.passed, k.boolean("passed"));
        CAVITY_ASSIGN(c.failures, k.strings("failures"));
        CAVITY_ASSIGN(const JsonObject metrics, k.object("metrics"));
        CAVITY_ASSIGN(const JsonObject tolerance, k.object("tolerance"));
        c.metrics = metrics.raw();
        c.tolerance = tolerance.raw();
        i.judged = std::move(c);
    }
    return i;
}

Result<RenderEntry> readRender(const JsonObject& rj) {
    RenderEntry r;
    CAVITY_ASSIGN(r.repetition, rj.integer("repetition", 0, 1000000));
    CAVITY_ASSIGN(r.error, rj.str("error"));
    CAVITY_ASSIGN(r.errorCode, rj.integer("error_code", 0, 255));
    CAVITY_ASSIGN(r.deterministic, rj.boolean("deterministic"));
    CAVITY_ASSIGN(const auto timings, rj.objects("timings"));
    for (const auto& t : timings) {
        CAVITY_ASSIGN(auto p, readPassTime(t));
        r.timings.push_back(std::move(p));
    }
    CAVITY_ASSIGN(const auto images, rj.objects("images"));
    for (const auto& ij : images) {
        CAVITY_ASSIGN(auto i, readImage(ij));
        r.images.push_back(std::move(i));
    }
    return r;
}

Result<ConfigEntry> readConfig(const JsonObject& cj) {
    ConfigEntry c;
    CAVITY_ASSIGN(c.id, cj.str("id"));
    CAVITY_ASSIGN(const int index, cj.integer("index", 0, 1 << 30));
    c.index = size_t(index);
    CAVITY_ASSIGN(c.key, cj.str("baseline_key"));
    CAVITY_ASSIGN(c.api, cj.str("api"));
    CAVITY_ASSIGN(c.device, cj.str("device"));
    CAVITY_ASSIGN(const auto renders, cj.objects("renders"));
    for (const auto& rj : renders) {
        CAVITY_ASSIGN(auto r, readRender(rj));
        c.renders.push_back(std::move(r));
    }
    return c;
}

}  // namespace

json replacedJson(const std::vector<ReplacedSource>& replaced) {
    json out = json::array();
    // path: where the file lives as a user finds it (kernels/... for a
    // built-in, the package's folder for one from disk), for the reports.
    for (const auto& r : replaced)
        out.push_back({{"name", r.name}, {"path", kernels::sourceLabel(r.name)}, {"file", r.file}, {"digest", r.digest}});
    return out;
}

Result<std::vector<ReplacedSource>> parseReplaced(const json& j, const std::string& path) {
    std::vector<ReplacedSource> out;
    if (!j.is_array()) return badInput(path + ": kernel_sources must be a list");
    for (const auto& r : j) {
        if (!r.is_object() || !r.contains("name") || !r.contains("file") || !r.contains("digest") || !r["name"].is_string() ||
            !r["file"].is_string() || !r["digest"].is_string())
            return badInput(path + ": kernel_sources has " + core::jsonText(r) + " (each {name, file, digest}, strings)");
        out.push_back({r["name"], r["file"], r["digest"]});
    }
    return out;
}

json toJson(const RenderManifest& m) {
    json devices = json::object(), errors = json::array(), configs = json::array();
    for (const auto& [api, d] : m.devices) devices[api] = toJson(d);
    for (const auto& e : m.backendErrors) errors.push_back({{"api", e.api}, {"code", e.code}, {"message", e.message}});
    for (const auto& c : m.configs) {
        json renders = json::array();
        for (const auto& r : c.renders) renders.push_back(toJson(r));
        configs.push_back({{"index", c.index}, {"id", c.id}, {"baseline_key", c.key}, {"api", c.api},
                           {"device", c.device}, {"renders", renders}});
    }
    return {{"schema", kRenderSchema},
            {"matrix", m.matrix},
            {"matrix_hash", m.matrixHash},
            {"git_commit", m.gitCommit},
            {"created_utc", m.createdUtc},
            {"command", m.command},
            {"shard", {m.shardIndex, m.shardCount}},
            {"filter", m.filter},
            {"repeat", m.repeat},
            {"kernel_sources", replacedJson(m.replaced)},
            {"kernel_packages", measure::packagesJson(m.packages)},
            {"seconds", m.seconds},
            {"image_format", kImageFormat},
            {"devices", devices},
            {"backend_errors", errors},
            {"configurations", configs}};
}

Result<RenderManifest> parseManifest(const json& j, const std::string& path) {
    if (!j.is_object() || !j.contains("schema") || j["schema"] != kRenderSchema)
        return badInput(path + ": not a render manifest (schema must be " + std::string(kRenderSchema) + ", found " +
                        (j.is_object() && j.contains("schema") ? core::jsonText(j["schema"]) : std::string("none")) + ")");
    CAVITY_ASSIGN(const JsonObject top, JsonObject::of(path, "", j));
    CAVITY_ASSIGN(const std::string format, top.str("image_format"));
    if (format != kImageFormat)
        return badInput(path + ": image_format " + core::shortDump(j["image_format"]) + " (this build reads " + kImageFormat + ")");
    RenderManifest m;
    CAVITY_ASSIGN(m.matrix, top.str("matrix"));
    CAVITY_ASSIGN(m.matrixHash, top.str("matrix_hash"));
    CAVITY_ASSIGN(m.gitCommit, top.str("git_commit"));
    CAVITY_ASSIGN(m.createdUtc, top.str("created_utc"));
    CAVITY_ASSIGN(m.command, top.str("command"));
    CAVITY_ASSIGN(const auto shard, top.integers("shard", 0, 1 << 20));
    if (shard.size() != 2) return top.bad("shard", "must be [I, N]");
    m.shardIndex = shard[0];
    m.shardCount = shard[1];
    CAVITY_ASSIGN(m.filter, top.str("filter"));
    CAVITY_ASSIGN(m.repeat, top.integer("repeat", 1, 1000000));
    CAVITY_ASSIGN(m.seconds, top.number("seconds", 0, 1e9));
    CAVITY_ASSIGN(const JsonObject devices, top.object("devices"));
    for (const auto& [api, raw] : devices.raw().items()) {
        CAVITY_ASSIGN(const JsonObject d, JsonObject::of(path, "devices." + api, raw));
        gpu::DeviceInfo info;
        info.api = api;
        CAVITY_ASSIGN(info.deviceName, d.str("name"));
        CAVITY_ASSIGN(info.driver, d.str("driver"));
        CAVITY_ASSIGN(info.apiVersion, d.str("api_version"));
        CAVITY_ASSIGN(info.vendor, d.str("vendor"));
        CAVITY_ASSIGN(info.softwareRenderer, d.boolean("software_renderer"));
        CAVITY_ASSIGN(info.uuid, d.str("uuid", ""));
        m.devices[api] = std::move(info);
    }
    CAVITY_ASSIGN(const auto errors, top.objects("backend_errors"));
    for (const auto& e : errors) {
        BackendError b;
        CAVITY_ASSIGN(b.api, e.str("api"));
        CAVITY_ASSIGN(b.code, e.integer("code", 0, 255));
        CAVITY_ASSIGN(b.message, e.str("message"));
        m.backendErrors.push_back(std::move(b));
    }
    CAVITY_ASSIGN(const auto configs, top.objects("configurations"));
    for (const auto& cj : configs) {
        CAVITY_ASSIGN(auto c, readConfig(cj));
        m.configs.push_back(std::move(c));
    }
    // Absent before --kernel-source was recorded: nothing replaced.
    if (j.contains("kernel_sources")) {
        CAVITY_ASSIGN(m.replaced, parseReplaced(j["kernel_sources"], path));
    }
    // Absent before packages were recorded.
    if (j.contains("kernel_packages")) {
        CAVITY_ASSIGN(m.packages, measure::parsePackages(j["kernel_packages"], path));
    }
    if (m.shardCount < 1 || m.shardIndex < 0 || m.shardIndex >= m.shardCount)
        return badInput(path + ": shard " + std::to_string(m.shardIndex) + "/" + std::to_string(m.shardCount) +
                        " (must be I/N with 0 <= I < N)");
    if (m.repeat < 1) return badInput(path + ": repeat " + std::to_string(m.repeat) + " (must be >= 1)");
    return m;
}

}  // namespace cavity::render
