#include "baselines.h"

#include "pipeline.h"
#include "sweep.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>

namespace cavity::gate {

using nlohmann::json;

std::string baselineKey(const RunConfig& c) {
    const std::string id = configId(c);
    // Drop "/<api>/<stage>".
    const auto stage = id.rfind('/');
    const auto api = id.rfind('/', stage - 1);
    return id.substr(0, api);
}

const std::vector<CheckedImage>& checkedImages() {
    static const std::vector<CheckedImage> images = {
        {"ao", ".exr", false},
        {"ao_blur", ".exr", false},
        {"color", ".png", true},
    };
    return images;
}

namespace {

bool icontains(const std::string& hay, const std::string& needle) {
    auto lower = [](std::string s) {
        std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
        return s;
    };
    return lower(hay).find(lower(needle)) != std::string::npos;
}

Result<json> readJson(const std::string& path) {
    std::ifstream f(path);
    if (!f) return badInput(path + ": cannot be read");
    try {
        return json::parse(f);
    } catch (const json::parse_error& e) {
        return badInput(path + ": does not parse: " + e.what());
    }
}

Status onlyKeys(const std::string& path, const std::string& where, const json& obj, const std::set<std::string>& allowed) {
    if (!obj.is_object()) return badInput(path + ": " + where + " must be an object");
    for (const auto& [k, v] : obj.items())
        if (!allowed.count(k)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            return badInput(path + ": unknown key '" + k + "' in " + where + " (allowed: " + list + ")");
        }
    return {};
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
        if (!(x >= 0)) return badInput(path + ": " + where + "." + k + " is " + v.dump() + ": tolerances must be >= 0");
        out[k] = x;
    }
    return out;
}

void apply(Tolerance& t, const std::map<std::string, double>& values) {
    for (const auto& [k, v] : values) t.*(toleranceFields().at(k)) = v;
}

template <class T>
Result<std::vector<T>> list(const std::string& path, const std::string& where, const json& j) {
    if (!j.is_array()) return badInput(path + ": " + where + " must be a list");
    std::vector<T> out;
    for (const auto& e : j) {
        try {
            out.push_back(e.get<T>());
        } catch (const json::exception&) {
            return badInput(path + ": " + where + " has a value of the wrong type: " + e.dump());
        }
    }
    return out;
}

}  // namespace

// ---- matrices ----

std::vector<RunConfig> Matrix::expand() const {
    std::vector<RunConfig> out;
    std::set<std::string> seen;
    for (const auto& g : groups) {
        std::vector<std::string> kernels = g.kernels;
        if (kernels.size() == 1 && kernels[0] == "all") kernels = aoKernels();
        for (const auto& scene : g.scenes)
            for (const auto& k : kernels)
                for (int n : g.samples)
                    for (int b : g.blurs)
                        for (bool half : g.half)
                            for (auto [w, h] : g.sizes)
                                for (auto api : g.apis)
                                    for (auto stage : g.stages) {
                                        RunConfig c;
                                        c.kernel = k;
                                        (void)setParam(c, "scene", scene);
                                        c.params["samples"] = n;
                                        c.params["blur"] = b;
                                        c.half = half;
                                        c.width = w;
                                        c.height = h;
                                        c.api = api;
                                        c.stage = stage;
                                        if (half && !supportsHalf(k)) continue;
                                        if (seen.insert(configId(c)).second) out.push_back(c);
                                    }
    }
    return out;
}

Result<Matrix> loadMatrix(const std::string& path, const std::string& name) {
    CAVITY_ASSIGN(json doc, readJson(path));
    if (!doc.is_object() || !doc.contains(name)) {
        std::string have;
        if (doc.is_object())
            for (const auto& [k, v] : doc.items()) have += (have.empty() ? "" : ", ") + k;
        return badInput("--matrix " + name + ": no such matrix in " + path + " (have: " + have + ")");
    }
    const json& m = doc[name];
    const std::string where = name;
    CAVITY_TRY(onlyKeys(path, where, m, {"description", "frames", "warmup", "groups"}));
    Matrix matrix;
    matrix.name = name;
    if (m.contains("frames")) matrix.frames = m["frames"].get<int>();
    if (m.contains("warmup")) matrix.warmup = m["warmup"].get<int>();
    if (!m.contains("groups") || !m["groups"].is_array()) return badInput(path + ": " + where + ".groups must be a list");
    int gi = 0;
    for (const auto& g : m["groups"]) {
        const std::string gw = where + ".groups[" + std::to_string(gi++) + "]";
        CAVITY_TRY(onlyKeys(path, gw, g,
                            {"scenes", "kernels", "samples", "blurs", "resolutions", "sizes", "apis", "stages"}));
        for (const char* key : {"scenes", "kernels", "samples", "blurs", "resolutions", "sizes", "apis", "stages"})
            if (!g.contains(key)) return badInput(path + ": " + gw + " lacks '" + key + "'");
        MatrixGroup grp;
        CAVITY_ASSIGN(grp.scenes, list<std::string>(path, gw + ".scenes", g["scenes"]));
        CAVITY_ASSIGN(grp.kernels, list<std::string>(path, gw + ".kernels", g["kernels"]));
        CAVITY_ASSIGN(grp.samples, list<int>(path, gw + ".samples", g["samples"]));
        CAVITY_ASSIGN(grp.blurs, list<int>(path, gw + ".blurs", g["blurs"]));
        CAVITY_ASSIGN(auto res, list<std::string>(path, gw + ".resolutions", g["resolutions"]));
        for (const auto& r : res) {
            if (r != "full" && r != "half") return badInput(path + ": " + gw + ".resolutions has '" + r + "' (full or half)");
            grp.half.push_back(r == "half");
        }
        CAVITY_ASSIGN(auto sizes, list<std::string>(path, gw + ".sizes", g["sizes"]));
        for (const auto& s : sizes) {
            CAVITY_ASSIGN(auto wh, parseResolution(path + ": " + gw + ".sizes", s));
            grp.sizes.push_back(wh);
        }
        CAVITY_ASSIGN(auto apis, list<std::string>(path, gw + ".apis", g["apis"]));
        for (const auto& a : apis) {
            if (a != "gl" && a != "vk") return badInput(path + ": " + gw + ".apis has '" + a + "' (gl or vk)");
            grp.apis.push_back(a == "gl" ? gpu::Api::OpenGL : gpu::Api::Vulkan);
        }
        CAVITY_ASSIGN(auto stages, list<std::string>(path, gw + ".stages", g["stages"]));
        for (const auto& s : stages) {
            if (s != "compute" && s != "fragment") return badInput(path + ": " + gw + ".stages has '" + s + "'");
            grp.stages.push_back(s == "compute" ? gpu::Stage::Compute : gpu::Stage::Fragment);
        }
        matrix.groups.push_back(std::move(grp));
    }
    for (const auto& c : matrix.expand()) {
        if (auto s = validate(c); !s) return badInput(path + ": matrix " + name + ": " + s.error().message);
    }
    return matrix;
}

// ---- manifest ----

Tolerance Manifest::forPipeline(const std::string& kernel, const std::string& deviceName) const {
    Tolerance t;
    if (auto it = rawPipelines.find("*"); it != rawPipelines.end()) apply(t, it->second);
    if (auto it = rawPipelines.find(kernel); it != rawPipelines.end()) apply(t, it->second);
    for (const auto& d : devices) {
        if (!icontains(deviceName, d.pattern)) continue;
        if (auto it = d.pipelines.find("*"); it != d.pipelines.end()) apply(t, it->second);
        if (auto it = d.pipelines.find(kernel); it != d.pipelines.end()) apply(t, it->second);
    }
    return t;
}

Result<Manifest> loadManifest(const std::string& path) {
    CAVITY_ASSIGN(json doc, readJson(path));
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
            CAVITY_TRY(onlyKeys(path, where, d, {"pattern", "pipelines", "note"}));
            if (!d.contains("pattern") || !d["pattern"].is_string())
                return badInput(path + ": " + where + " needs a string 'pattern'");
            Manifest::DeviceOverride o{d["pattern"].get<std::string>(), {}};
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

Result<Budgets> loadBudgets(const std::string& path) {
    CAVITY_ASSIGN(json doc, readJson(path));
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
                        return badInput(path + ": budget " + id + " " + pass + " is " + ms.dump() + ": must be a number > 0");
                    dev.configs[id][pass] = ms.get<double>();
                }
            }
        }
        b.devices.push_back(std::move(dev));
    }
    return b;
}

}  // namespace cavity::gate
