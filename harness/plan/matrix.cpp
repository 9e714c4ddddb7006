#include "nearest.h"
#include "plan/matrix.h"
#include "core/regex_guard.h"

#include "plan/axes.h"

#include "pipeline/config_id.h"
#include "core/digest.h"
#include "core/json_input.h"
#include "pipeline/pipeline.h"
#include "plan/sweep.h"

#include <algorithm>
#include <map>
#include <optional>
#include <regex>
#include <set>

namespace cavity::plan {

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

ImageShape checkedShape(const RunConfig& c, const std::string& image) {
    const bool half = c.half && supportsHalf(c.kernel) && image == "ao";
    return {half ? (c.width + 1) / 2 : c.width, half ? (c.height + 1) / 2 : c.height, image == "color" ? 4 : 1};
}

std::string shapeText(const ImageShape& s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height) + "x" + std::to_string(s.channels);
}


std::vector<RunConfig> Matrix::expand() const {
    std::vector<RunConfig> out;
    std::set<std::string> seen;
    for (const auto& g : groups) {
        Axes axes;
        axes.scenes = g.scenes;
        axes.kernels = g.kernels.size() == 1 && g.kernels[0] == "all" ? aoKernels() : g.kernels;
        axes.params = {{"blur", std::vector<double>(g.blurs.begin(), g.blurs.end())}};
        if (g.samplesGiven) axes.params.insert(axes.params.begin(), {"samples", std::vector<double>(g.samples.begin(), g.samples.end())});
        axes.params.insert(axes.params.end(), g.params.begin(), g.params.end());
        axes.half = g.half;
        axes.sizes = g.sizes;
        axes.apis = g.apis;
        axes.stages = g.stages;
        // An empty list is an empty product (the expander would keep the
        // default there); loadMatrix has checked every scene name.
        if (g.scenes.empty() || axes.kernels.empty() || (g.samplesGiven && g.samples.empty()) || g.blurs.empty() || g.half.empty() ||
            g.sizes.empty() || g.apis.empty() || g.stages.empty())
            continue;
        auto configs = expandAxes(axes);
        if (!configs) continue;
        for (auto& c : *configs)
            if (seen.insert(configId(c)).second) out.push_back(std::move(c));
    }
    return out;
}

namespace {

// A value as a message names it: a bare NaN or Infinity reads as null
// (core/json_file.h), so null is named as all three.
std::string shownValue(const nlohmann::json& v) { return v.is_null() ? "null (or a NaN or Infinity)" : core::jsonText(v); }

// "params": {"radius": [2, 4]}: kernel parameters other than samples and
// blur (which have keys of their own), each a list of numbers (an enum's
// also of its choices' names); their ranges
// are checked with every configuration by validate().
Result<std::vector<std::pair<std::string, std::vector<double>>>> parseParams(const std::string& path,
                                                                           const std::string& gw, const json& g) {
    std::vector<std::pair<std::string, std::vector<double>>> out;
    if (!g.contains("params")) return out;
    if (!g["params"].is_object()) return badInput(path + ": " + gw + ".params must be an object of lists");
    for (const auto& [name, values] : g["params"].items()) {
        const std::map<std::string, std::string> ownKey = {{"samples", "samples"}, {"blur", "blurs"}, {"scene", "scenes"}};
        if (ownKey.count(name))
            return badInput(path + ": " + gw + ".params has '" + name + "': give it in the group's own key '" +
                            ownKey.at(name) + "', not under params");
        if (!kernels::findParam(name)) {
            std::vector<std::string> known;
            for (const auto& p : kernels::paramDecls())
                if (p.name != "samples" && p.name != "blur" && p.name != "scene") known.push_back(p.name);
            const std::string near = kernels::findParam(name) ? "" : nearestWord(name, known);
            return badInput(path + ": " + gw + ".params has '" + name + "'" +
                            (near.empty() ? "" : " (did you mean " + near + "?)") +
                            " (a kernel parameter other than samples, blur and scene; see cavity run --help, and "
                            "load the package that declares it with --kernels DIR)");
        }
        if (!values.is_array() || values.empty())
            return badInput(path + ": " + gw + ".params." + name + " must be a non-empty list of numbers");
        // A number, or an enum's choice by name as on the command line.
        const kernels::ParamDecl& decl = *kernels::findParam(name);
        std::vector<double> list;
        for (const auto& v : values) {
            if (v.is_string() && decl.type == kernels::ParamType::Enum) {
                auto parsed = kernels::parseValue(decl, v.get<std::string>());
                if (!parsed)
                    return badInput(path + ": " + gw + ".params." + name + " has " + shownValue(v) + ": must be " +
                                    kernels::allowedValues(decl));
                list.push_back(*parsed);
            } else if (v.is_boolean() && decl.type == kernels::ParamType::Bool) {   // as kernel.toml takes it
                list.push_back(v.get<bool>() ? 1 : 0);
            } else if (v.is_number()) {
                list.push_back(kernels::canonicalValue(decl, v.get<double>()));
            } else {
                return badInput(path + ": " + gw + ".params." + name + " has " + shownValue(v) + ": must be " +
                                kernels::allowedValues(decl));
            }
            // [0, "none"] or [true, 1]: one value written twice, which
            // would run its configurations twice under one id.
            if (std::count(list.begin(), list.end(), list.back()) > 1)
                return badInput(path + ": " + gw + ".params." + name + " has " + shownValue(v) +
                                " twice (another entry names the same value)");
        }
        out.emplace_back(name, std::move(list));
    }
    return out;
}

Result<MatrixGroup> parseGroup(const std::string& path, const std::string& gw, const json& g) {
    CAVITY_TRY(onlyKeys(path, gw, g, {"scenes", "kernels", "samples", "blurs", "params", "resolutions", "sizes", "apis", "stages"}));
    for (const char* key : {"scenes", "kernels", "blurs", "resolutions", "sizes", "apis", "stages"})
        if (!g.contains(key)) return badInput(path + ": " + gw + " lacks '" + key + "'");
    // An empty list selects nothing, and a gate of nothing is no verdict;
    // a value twice ([4, 4.0]) would be one configuration written twice.
    for (const char* key : {"scenes", "kernels", "samples", "blurs", "resolutions", "sizes", "apis", "stages"}) {
        if (!g.contains(key) || !g[key].is_array()) continue;
        if (g[key].empty()) return badInput(path + ": " + gw + "." + key + " is empty (a non-empty list is expected)");
        for (const auto& v : g[key])
            if (std::count(g[key].begin(), g[key].end(), v) > 1)
                return badInput(path + ": " + gw + "." + key + " has " + shownValue(v) + " twice");
    }
    MatrixGroup grp;
    CAVITY_ASSIGN(const JsonObject gf, JsonObject::of(path, gw, g));
    CAVITY_ASSIGN(grp.scenes, gf.strings("scenes"));
    CAVITY_ASSIGN(grp.kernels, gf.strings("kernels"));
    // Ranges are the declarations' (validate() checks each configuration again).
    grp.samplesGiven = g.contains("samples");
    if (grp.samplesGiven) {
        CAVITY_ASSIGN(grp.samples, gf.integers("samples", 1, 1 << 20));
    }
    CAVITY_ASSIGN(grp.blurs, gf.integers("blurs", 0, 1 << 20));
    CAVITY_ASSIGN(grp.params, parseParams(path, gw, g));
    CAVITY_ASSIGN(auto res, gf.strings("resolutions"));
    for (const auto& r : res) {
        if (r != "full" && r != "half") return badInput(path + ": " + gw + ".resolutions has '" + r + "' (full or half)");
        grp.half.push_back(r == "half");
    }
    CAVITY_ASSIGN(auto sizes, gf.strings("sizes"));
    for (const auto& s : sizes) {
        CAVITY_ASSIGN(auto wh, parseResolution(path + ": " + gw + ".sizes", s));
        grp.sizes.push_back(wh);
    }
    CAVITY_ASSIGN(auto apis, gf.strings("apis"));
    for (const auto& a : apis) {
        if (a != "gl" && a != "vk") return badInput(path + ": " + gw + ".apis has '" + a + "' (gl or vk)");
        grp.apis.push_back(a == "gl" ? gpu::Api::OpenGL : gpu::Api::Vulkan);
    }
    CAVITY_ASSIGN(auto stages, gf.strings("stages"));
    for (const auto& s : stages) {
        if (s != "compute" && s != "fragment") return badInput(path + ": " + gw + ".stages has '" + s + "'");
        grp.stages.push_back(s == "compute" ? gpu::Stage::Compute : gpu::Stage::Fragment);
    }
    return grp;
}

}  // namespace

Result<Matrix> loadMatrix(const std::string& path, const std::string& name) {
    CAVITY_ASSIGN(json doc, readJsonFile(path));
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
    const std::string text = core::jsonText(m);
    matrix.hash = digestText(fnv1a64(text.data(), text.size()));
    // The same ranges as cavity run's --frames and --warmup.
    CAVITY_ASSIGN(const JsonObject fields, JsonObject::of(path, where, m));
    CAVITY_ASSIGN(matrix.frames, fields.integer("frames", 1, 100000, matrix.frames));
    CAVITY_ASSIGN(matrix.warmup, fields.integer("warmup", 0, 10000, matrix.warmup));
    if (!m.contains("groups") || !m["groups"].is_array()) return badInput(path + ": " + where + ".groups must be a list");
    int gi = 0;
    for (const auto& g : m["groups"]) {
        const std::string gw = where + ".groups[" + std::to_string(gi++) + "]";
        CAVITY_ASSIGN(MatrixGroup grp, parseGroup(path, gw, g));
        // A value no pass of the group reads changes nothing it renders.
        Matrix one;
        one.groups = {grp};
        const auto configs = one.expand();
        // Samples too: "samples": [8] for kernels without a sample count ran
        // their one configuration under an id that says n16.
        std::vector<std::string> given;
        if (grp.samplesGiven) given.push_back("samples");
        for (const auto& [name, values] : grp.params) given.push_back(name);
        for (const auto& name : given)
            if (!configs.empty() && std::none_of(configs.begin(), configs.end(),
                                                 [&](const RunConfig& c) { return pipeline::pipelineReads(c, name); }))
                return badInput(path + ": " + gw + (name == "samples" ? ".samples" : ".params." + name) +
                                ": no kernel of the group reads it");
        matrix.groups.push_back(std::move(grp));
    }
    for (const auto& c : matrix.expand()) {
        if (auto s = validate(c); !s) return badInput(path + ": matrix " + name + ": " + s.error().message);
    }
    return matrix;
}

bool inShard(size_t index, int shardIndex, int shardCount) {
    return shardCount <= 1 || int(index % size_t(shardCount)) == shardIndex;
}

Result<std::vector<MatrixEntry>> selectEntries(const Matrix& m, int shardIndex, int shardCount,
                                               const std::string& filter) {
    std::optional<std::regex> re;
    if (const std::string why = core::nestedQuantifierError("--filter", filter); !why.empty()) return badInput(why);
    if (!filter.empty()) {
        try {
            re.emplace(filter);
        } catch (const std::regex_error& e) {
            return badInput("--filter " + filter + ": not a regular expression (" + e.what() + ")");
        }
    }
    std::vector<MatrixEntry> out;
    const auto all = m.expand();
    size_t matches = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        if (re && !std::regex_search(configId(all[i]), *re)) continue;
        ++matches;
        if (inShard(i, shardIndex, shardCount)) out.push_back({i, all[i]});
    }
    // A filter that selects nothing would pass as "all 0 configurations
    // passed"; an empty shard of a larger matrix is fine.
    if (re && matches == 0)
        return badInput("--filter " + filter + ": matches none of the " + std::to_string(all.size()) +
                        " configurations of matrix " + m.name + " (ids read like " +
                        (all.empty() ? std::string("?") : configId(all.front())) + ")");
    return out;
}

}  // namespace cavity::plan
