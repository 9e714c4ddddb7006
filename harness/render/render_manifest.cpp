#include "render/render_manifest.h"

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

// One timing of a manifest; the interval and the statistics are absent from
// older ones.
PassTime readPassTime(const json& t) {
    auto num = [&](const char* k) { return t.contains(k) && t.at(k).is_number() ? t.at(k).get<double>() : NAN; };
    auto stats = measure::shaderStatsFromJson(t.contains("shader_stats") ? t.at("shader_stats") : json());
    return {t.at("pass"), t.at("median_ms"), t.at("clock"), num("ci_low_ms"), num("ci_high_ms"), std::move(stats)};
}

}  // namespace

json replacedJson(const std::vector<ReplacedSource>& replaced) {
    json out = json::array();
    for (const auto& r : replaced) out.push_back({{"name", r.name}, {"file", r.file}, {"digest", r.digest}});
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
    if (j.value("image_format", "") != kImageFormat)
        return badInput(path + ": image_format " + j.value("image_format", "(none)") + " (this build reads " +
                        kImageFormat + ")");
    RenderManifest m;
    // nlohmann's messages name the missing key or the wrong type; the
    // configuration named in front says where.
    std::string where = "the top level";
    try {
        m.matrix = j.at("matrix");
        m.matrixHash = j.at("matrix_hash");
        m.gitCommit = j.at("git_commit");
        m.createdUtc = j.at("created_utc");
        m.command = j.at("command");
        m.shardIndex = j.at("shard").at(0);
        m.shardCount = j.at("shard").at(1);
        m.filter = j.at("filter");
        m.repeat = j.at("repeat");
        m.seconds = j.at("seconds");
        for (const auto& [api, d] : j.at("devices").items())
            m.devices[api] = {api, d.at("name"), d.at("driver"), d.at("api_version"), d.at("vendor"),
                              d.at("software_renderer"), d.value("uuid", std::string())};
        for (const auto& e : j.at("backend_errors")) m.backendErrors.push_back({e.at("api"), e.at("code"), e.at("message")});
        for (const auto& cj : j.at("configurations")) {
            ConfigEntry c;
            where = "a configuration";
            c.id = cj.at("id");
            where = c.id;
            c.index = cj.at("index");
            c.key = cj.at("baseline_key");
            c.api = cj.at("api");
            c.device = cj.at("device");
            for (const auto& rj : cj.at("renders")) {
                RenderEntry r;
                r.repetition = rj.at("repetition");
                r.error = rj.at("error");
                r.errorCode = rj.at("error_code");
                r.deterministic = rj.at("deterministic");
                for (const auto& t : rj.at("timings")) r.timings.push_back(readPassTime(t));
                for (const auto& ij : rj.at("images")) {
                    ImageEntry i;
                    i.name = ij.at("name");
                    if (!ij.at("file").is_null()) i.file = ij.at("file");
                    i.stored = {ij.at("width"), ij.at("height"), ij.at("channels"), ij.at("digest"), ij.at("bytes")};
                    if (ij.contains("judged")) {
                        const json& k = ij.at("judged");
                        i.judged = RemoteCheck{k.at("reference"), k.at("reference_digest"), k.at("passed"),
                                               k.at("failures"), k.at("metrics"), k.at("tolerance")};
                        if (!i.judged->metrics.is_object() || !i.judged->tolerance.is_object())
                            return badInput(path + ": malformed at " + where + ": judged." + i.name +
                                            ": metrics and tolerance must be objects");
                    }
                    r.images.push_back(std::move(i));
                }
                c.renders.push_back(std::move(r));
            }
            m.configs.push_back(std::move(c));
        }
    } catch (const json::exception& e) {
        return badInput(path + ": malformed at " + where + ": " + e.what());
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
