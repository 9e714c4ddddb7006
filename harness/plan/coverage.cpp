#include "plan/coverage.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <set>

namespace cavity::plan {

namespace {

bool writesMipChain(const kernels::KernelDecl& k) {
    return std::any_of(k.outputs.begin(), k.outputs.end(), [](const auto& o) { return o.mipLevels > 1; });
}

std::string valueName(const kernels::ParamDecl& d, double v) {
    if (d.type == kernels::ParamType::Enum) {
        const auto i = size_t(v);
        return i < d.choices.size() ? d.choices[i] : std::to_string(i);
    }
    return std::to_string(int(v));
}

// The values a bool or enum parameter can take; none for the others.
std::vector<double> optionValues(const kernels::ParamDecl& d) {
    if (d.type == kernels::ParamType::Bool) return {0, 1};
    std::vector<double> v;
    if (d.type == kernels::ParamType::Enum)
        for (size_t i = 0; i < d.choices.size(); ++i) v.push_back(double(i));
    return v;
}

// The paths any valid configuration can reach: each AO kernel's default
// configuration on each API, stage, resolution and with and without its
// blur, and each of those with one parameter moved to each value of a small
// domain (a bool, an enum, an integer of a few values: those that pick a
// pass, like the interleaved layers or the fused tail). A kernel's stage or
// option that no configuration can reach (the per-level pyramid's own
// switch, which picks that pass) is no hole in the gate.
const std::set<std::string>& reachable() {
    static const std::set<std::string> paths = [] {
        std::vector<std::pair<std::string, std::vector<double>>> moves;
        for (const auto& d : kernels::paramDecls()) {
            std::vector<double> values = optionValues(d);
            if (values.empty() && d.type == kernels::ParamType::Int && d.max - d.min <= 7)
                for (double v = d.min; v <= d.max; ++v) values.push_back(v);
            if (!values.empty()) moves.emplace_back(d.name, values);
        }
        std::set<std::string> out;
        auto probe = [&](const RunConfig& c) {
            if (!pipeline::validate(c)) return;
            for (const auto& p : pathsOf(c)) out.insert(p.text());
        };
        for (const auto& k : kernels::all()) {
            if (k.role != kernels::Role::Ao) continue;
            for (const auto api : {gpu::Api::OpenGL, gpu::Api::Vulkan})
                for (const auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment})
                    for (const bool half : {false, true})
                        for (const int blur : {0, 4}) {
                            RunConfig c;
                            c.kernel = k.name;
                            c.api = api;
                            c.stage = stage;
                            c.half = half;
                            c.params["blur"] = blur;
                            probe(c);
                            for (const auto& [name, values] : moves)
                                for (double v : values) {
                                    RunConfig moved = c;
                                    moved.params[name] = v;
                                    probe(moved);
                                }
                        }
        }
        return out;
    }();
    return paths;
}

}  // namespace

std::vector<CodePath> declaredPaths(const kernels::KernelDecl& k) {
    std::vector<CodePath> out;
    if (k.role == kernels::Role::Reference) return out;
    // Each API too: the GL and Vulkan builds of a shader differ where it
    // asks (#if defined(VULKAN)).
    for (const char* api : {"gl", "vk"}) {
        out.push_back({k.name, std::string("compute/") + api, "stage"});
        if (!writesMipChain(k)) out.push_back({k.name, std::string("fragment/") + api, "stage"});
    }
    for (const auto& p : k.params)
        for (double v : optionValues(*p.decl))
            out.push_back({k.name, p.name() + "=" + valueName(*p.decl, v),
                           p.type() == kernels::ParamType::Bool ? "bool parameter" : "enum parameter"});
    const auto& can = reachable();
    std::erase_if(out, [&](const CodePath& p) { return !can.count(p.text()); });
    for (const auto& path : k.paths) out.push_back({k.name, path.name, path.whenText});
    return out;
}

std::vector<CodePath> pathsOf(const RunConfig& c) {
    std::vector<CodePath> out;
    for (const auto& pass : pipeline::buildPasses(c)) {
        const kernels::KernelDecl* k = kernels::find(pass.kernel);
        if (!k || k->role == kernels::Role::Reference) continue;
        const bool compute = pipeline::passStage(*k, c) == gpu::Stage::Compute;   // as PassChain runs it
        out.push_back({k->name, std::string(compute ? "compute" : "fragment") + "/" + gpu::apiName(c.api), "stage"});
        kernels::ParamValues values;
        for (const auto& p : k->params) {
            values[p.name()] = c.param(p.name());
            if (!optionValues(*p.decl).empty())
                out.push_back({k->name, p.name() + "=" + valueName(*p.decl, values[p.name()]), ""});
        }
        values["compute"] = compute ? 1 : 0;
        values["width"] = pass.half ? (c.width + 1) / 2 : c.width;   // as PassChain sizes it
        values["height"] = pass.half ? (c.height + 1) / 2 : c.height;
        values["half"] = c.half ? 1 : 0;
        for (const auto& path : k->paths)
            if (path.when && path.when(values)) out.push_back({k->name, path.name, path.whenText});
    }
    return out;
}

std::map<std::string, std::string> reachedBy(const std::vector<Matrix>& matrices) {
    std::map<std::string, std::string> reached;
    for (const auto& m : matrices)
        for (const auto& c : m.expand())
            for (const auto& p : pathsOf(c)) reached.emplace(p.text(), m.name + ": " + pipeline::configId(c));
    return reached;
}

std::vector<CodePath> uncovered(const std::vector<Matrix>& matrices) {
    const auto reached = reachedBy(matrices);
    std::vector<CodePath> out;
    for (const auto& k : kernels::all())
        for (const auto& p : declaredPaths(k))
            if (!reached.count(p.text())) out.push_back(p);
    return out;
}

}  // namespace cavity::plan
