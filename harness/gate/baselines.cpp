#include "gate/baselines.h"

#include "core/json_input.h"
#include "kernel.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <fstream>
#include <set>

namespace cavity::gate {

using nlohmann::json;

namespace {

bool icontains(const std::string& hay, const std::string& needle) {
    auto lower = [](std::string s) {
        std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
        return s;
    };
    return lower(hay).find(lower(needle)) != std::string::npos;
}

const std::map<std::string, double Tolerance::*>& toleranceFields() {
    static const std::map<std::string, double Tolerance::*> f = {
        {"max_abs", &Tolerance::maxAbs},
        {"mean_abs", &Tolerance::meanAbs},
        {"rmse", &Tolerance::rmse},
        {"psnr_min", &Tolerance::psnrMin},
        {"pixel_threshold", &Tolerance::pixelThreshold},
        {"over_threshold_share", &Tolerance::overThresholdShare},
        {"ssim_min", &Tolerance::ssimMin},
        {"flip_mean_max", &Tolerance::flipMeanMax},
        {"differing_delta", &Tolerance::differingDelta},
        {"differing_share_max", &Tolerance::differingShareMax},
        {"sized_for_pixels", &Tolerance::sizedForPixels},
    };
    return f;
}

Result<std::map<std::string, double>> readTolerances(const std::string& path, const std::string& where, const json& obj) {
    std::set<std::string> allowed;
    for (const auto& [k, v] : toleranceFields()) allowed.insert(k);
    CAVITY_TRY(onlyKeys(path, where, obj, allowed));
    std::map<std::string, double> out;
    for (const auto& [k, v] : obj.items()) {
        if (!v.is_number()) return badInput(path + ": " + where + "." + k + " must be a number");
        const double x = v.get<double>();
        if (!(x >= 0)) return badInput(path + ": " + where + "." + k + " is " + core::jsonText(v) + ": tolerances must be >= 0");
        if (k == "differing_delta" && (x != std::floor(x) || x > 255))
            return badInput(path + ": " + where + "." + k + " is " + core::jsonText(v) + ": must be an integer in 0..255 (8-bit steps)");
        if (k == "sized_for_pixels" && x != std::floor(x))
            return badInput(path + ": " + where + "." + k + " is " + core::jsonText(v) + ": must be a whole number of pixels (0: any size)");
        if ((k == "differing_share_max" || k == "over_threshold_share") && x > 1)
            return badInput(path + ": " + where + "." + k + " is " + core::jsonText(v) + ": must be a share in 0..1");
        out[k] = x;
    }
    return out;
}

void apply(Tolerance& t, const std::map<std::string, double>& values) {
    for (const auto& [k, v] : values) t.*(toleranceFields().at(k)) = v;
}

}  // namespace

// ---- manifest ----

Tolerance sizedFor(Tolerance t, long long pixels) {
    if (t.sizedForPixels <= 0 || pixels <= 0) return t;
    const double f = t.sizedForPixels / double(pixels);
    t.meanAbs *= f;
    t.rmse *= std::sqrt(f);
    t.overThresholdShare = std::min(1.0, t.overThresholdShare * f);
    t.sizedForPixels = double(pixels);
    return t;
}

Tolerance Manifest::forPipeline(const std::string& kernel, const std::string& deviceName, bool ownClass) const {
    Tolerance t;
    if (auto it = rawPipelines.find("*"); it != rawPipelines.end()) apply(t, it->second);
    if (auto it = rawPipelines.find(kernel); it != rawPipelines.end()) apply(t, it->second);
    for (const auto& d : devices) {
        if (!icontains(deviceName, d.pattern) || (ownClass && !d.everyReference)) continue;
        if (auto it = d.pipelines.find("*"); it != d.pipelines.end()) apply(t, it->second);
        if (auto it = d.pipelines.find(kernel); it != d.pipelines.end()) apply(t, it->second);
    }
    return t;
}

Result<Manifest> loadManifest(const std::string& path) {
    CAVITY_ASSIGN(json doc, readJsonFile(path));
    CAVITY_TRY(onlyKeys(path, "the top level", doc, {"version", "pipelines", "devices", "note"}));
    Manifest m;
    if (doc.contains("pipelines")) {
        CAVITY_TRY(onlyKeys(path, "pipelines", doc["pipelines"], [] {
            std::set<std::string> s{"*"};
            for (const auto& k : kernels::all()) s.insert(k.name);
            return s;
        }()));
        for (const auto& [k, v] : doc["pipelines"].items()) {
            CAVITY_ASSIGN(m.rawPipelines[k], readTolerances(path, "pipelines." + k, v));
        }
    }
    if (doc.contains("devices")) {
        if (!doc["devices"].is_array()) return badInput(path + ": devices must be a list");
        int i = 0;
        for (const auto& d : doc["devices"]) {
            const std::string where = "devices[" + std::to_string(i++) + "]";
            CAVITY_TRY(onlyKeys(path, where, d, {"pattern", "pipelines", "note", "scope"}));
            if (!d.contains("pattern") || !d["pattern"].is_string())
                return badInput(path + ": " + where + " needs a string 'pattern'");
            Manifest::DeviceOverride o{d["pattern"].get<std::string>(), {}};
            if (d.contains("scope")) {
                if (d["scope"] != "baselines" && d["scope"] != "all")
                    return badInput(path + ": " + where + ".scope is " + core::jsonText(d["scope"]) +
                                    ": must be \"baselines\" (against the stored baselines only) or \"all\"");
                o.everyReference = d["scope"] == "all";
            }
            if (d.contains("pipelines"))
                for (const auto& [k, v] : d["pipelines"].items()) {
                    CAVITY_ASSIGN(o.pipelines[k], readTolerances(path, where + ".pipelines." + k, v));
                }
            m.devices.push_back(std::move(o));
        }
    }
    return m;
}

// ---- budgets ----

std::optional<double> Budgets::find(const std::string& deviceName, const std::string& id, const std::string& pass) const {
    for (const auto& d : devices) {
        if (!icontains(deviceName, d.pattern)) continue;
        auto c = d.configs.find(id);
        if (c == d.configs.end()) continue;
        auto p = c->second.find(pass);
        if (p != c->second.end()) return p->second;
    }
    return std::nullopt;
}

const Budgets::Device* Budgets::entryFor(const std::string& deviceName) const {
    for (const auto& d : devices)
        if (icontains(deviceName, d.pattern)) return &d;
    return nullptr;
}

Result<Budgets> loadBudgets(const std::string& path) {
    CAVITY_ASSIGN(json doc, readJsonFile(path));
    CAVITY_TRY(onlyKeys(path, "the top level", doc, {"version", "devices", "note"}));
    Budgets b;
    if (!doc.contains("devices")) return b;
    if (!doc["devices"].is_array()) return badInput(path + ": devices must be a list");
    int i = 0;
    for (const auto& d : doc["devices"]) {
        const std::string where = "devices[" + std::to_string(i++) + "]";
        CAVITY_TRY(onlyKeys(path, where, d, {"pattern", "budgets_ms", "note", "measured_on"}));
        if (!d.contains("pattern") || !d["pattern"].is_string())
            return badInput(path + ": " + where + " needs a string 'pattern'");
        Budgets::Device dev{d["pattern"].get<std::string>(), {}};
        if (d.contains("budgets_ms")) {
            if (!d["budgets_ms"].is_object()) return badInput(path + ": " + where + ".budgets_ms must be an object");
            for (const auto& [id, passes] : d["budgets_ms"].items()) {
                if (!passes.is_object()) return badInput(path + ": " + where + ".budgets_ms[\"" + id + "\"] must be an object");
                for (const auto& [pass, ms] : passes.items()) {
                    if (!ms.is_number() || !(ms.get<double>() > 0))
                        return badInput(path + ": budget " + id + " " + pass + " is " + core::jsonText(ms) + ": must be a number > 0");
                    dev.configs[id][pass] = ms.get<double>();
                }
            }
        }
        b.devices.push_back(std::move(dev));
    }
    return b;
}

}  // namespace cavity::gate
