#include "config.h"

#include "pipeline.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>

namespace cavity {

namespace {

using kernels::findParam;

// A parameter's value in this configuration: given, or the AO kernel's
// default where the kernel reads it, or the declaration's.
double paramOr(const RunConfig& c, const std::string& name) {
    if (auto it = c.params.find(name); it != c.params.end()) return it->second;
    if (const auto* k = kernels::find(c.kernel))
        for (const auto& p : k->params)
            if (p.name() == name) return p.def;
    const auto* p = findParam(name);
    return p ? p->def : 0.0;
}

std::string aoKernelNames() {
    std::string s;
    for (const auto& k : kernels::all())
        if (k.role == kernels::Role::Ao || k.role == kernels::Role::Reference) s += (s.empty() ? "" : ", ") + k.name;
    return s;
}

// The AO kernels that read only the G-buffer.
std::string screenSpaceAoNames() {
    std::string s;
    for (const auto& k : kernels::all())
        if (k.role == kernels::Role::Ao && !kernels::evaluatesScene(k)) s += (s.empty() ? "" : ", ") + k.name;
    return s;
}

}  // namespace

std::string RunConfig::scene() const {
    return kernels::valueText(*findParam("scene"), paramOr(*this, "scene"));
}
int RunConfig::samples() const { return kernels::asInt(paramOr(*this, "samples")); }
int RunConfig::blur() const { return kernels::asInt(paramOr(*this, "blur")); }
std::string RunConfig::gbufferSource() const { return imported() ? "import" : raster ? "raster" : "sdf"; }

std::string importStem(const std::string& path) {
    std::string stem = std::filesystem::path(path).stem().string();
    for (char& ch : stem)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '_' && ch != '-') ch = '_';
    return stem;
}

namespace {

// A parameter value as the id writes it: the shortest text that reads back
// as the same double (0.3, not 0.29999999999999999), or an Enum's choice name.
std::string valueText(const std::string& name, double v) {
    const auto* p = findParam(name);
    if (p && p->type == kernels::ParamType::Enum) return kernels::valueText(*p, v);
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

// Whether a given parameter value changes what the pipeline runs: it differs
// from the default of some kernel of the pipeline that declares it, or no
// kernel of the pipeline declares it (it is still part of what was asked).
bool differsFromDefault(const RunConfig& c, const std::string& name, double v) {
    bool declared = false;
    for (const auto& spec : buildPasses(c)) {
        const auto* k = kernels::find(spec.kernel);
        if (!k) continue;
        for (const auto& p : k->params)
            if (p.name() == name) {
                declared = true;
                if (p.def != v) return true;
            }
    }
    return !declared;
}

}  // namespace

// Samples and blur keep their short segments (n16, b4) so that ids at the
// defaults, and the baseline paths derived from them, read as they always
// did; a kernel without a sample count names its own count instead
// (ground_truth: rays1024). Every other parameter appears only when it
// differs from its default, as one "name=value" segment each, in name order
// after the blur segment: corner/alchemy/n16/b4/radius=0.3/full/...
std::string configId(const RunConfig& c) {
    const std::string scene = c.imported() ? importStem(c.gbufferFile) + "+import" : c.scene() + (c.raster ? "+raster" : "");
    const auto* k = kernels::find(c.kernel);
    auto declares = [&](const std::string& name) {
        return k && std::any_of(k->params.begin(), k->params.end(), [&](const auto& p) { return p.name() == name; });
    };
    std::string count = "n";
    count += std::to_string(c.samples());
    std::string countParam = "samples";
    if (!declares("samples") && declares("rays")) {
        countParam = "rays";
        count = "rays";
        count += valueText("rays", paramOr(c, "rays"));
    }
    std::string extra;
    for (const auto& [name, v] : c.params) {
        if (name == "scene" || name == "blur" || name == countParam) continue;
        if (!differsFromDefault(c, name, v)) continue;
        extra += "/" + name + "=" + valueText(name, v);
    }
    return scene + "/" + c.kernel + "/" + count + "/b" + std::to_string(c.blur()) + extra +
           "/" + (c.half ? "half" : "full") + "/" + std::to_string(c.width) + "x" + std::to_string(c.height) +
           "/" + gpu::apiName(c.api) + "/" + (c.stage == gpu::Stage::Compute ? "compute" : "fragment");
}

Result<std::pair<int, int>> parseResolution(const std::string& flag, const std::string& text) {
    const std::string allowed = ": must be WIDTHxHEIGHT with each in 1.." + std::to_string(kMaxResolution);
    const auto x = text.find('x');
    if (x == std::string::npos) return badInput(flag + " " + text + allowed);
    int w = 0, h = 0;
    const char* b = text.data();
    auto r1 = std::from_chars(b, b + x, w);
    auto r2 = std::from_chars(b + x + 1, b + text.size(), h);
    if (r1.ec != std::errc() || r1.ptr != b + x || r2.ec != std::errc() || r2.ptr != b + text.size() || w < 1 ||
        h < 1 || w > kMaxResolution || h > kMaxResolution)
        return badInput(flag + " " + text + allowed);
    return std::pair{w, h};
}

bool isKernelParam(const std::string& name) { return findParam(name) != nullptr; }

Status setParam(RunConfig& c, const std::string& name, const std::string& text) {
    const auto* p = findParam(name);
    if (!p) return badInput("--" + name + ": unknown flag");
    CAVITY_ASSIGN(c.params[name], kernels::parseValue(*p, text));
    return {};
}

Status validate(const RunConfig& c) {
    const auto* k = kernels::find(c.kernel);
    // "reference" kernels (the ground truth) run in the AO slot when named;
    // sweeps over "every AO kernel" leave them out (they are slow by design).
    if (!k || (k->role != kernels::Role::Ao && k->role != kernels::Role::Reference)) return badInput("--kernel " + c.kernel + ": unknown kernel (have: " + aoKernelNames() + ")");
    if (c.width < 1 || c.height < 1 || c.width > kMaxResolution || c.height > kMaxResolution)
        return badInput("--res " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                        ": must be WIDTHxHEIGHT with each in 1.." + std::to_string(kMaxResolution));
    if (c.raster && c.imported()) return badInput("--gbuffer: raster and import exclude each other");
    // A pass that evaluates the analytic scene itself has no scene to
    // evaluate when the G-buffer is a capture.
    if (c.imported())
        for (const auto& spec : buildPasses(c))
            if (const auto* d = kernels::find(spec.kernel); d && kernels::evaluatesScene(*d))
                return badInput("--kernel " + c.kernel + ": pass " + spec.name + " (" + d->name +
                                        ") evaluates the analytic scene, so it cannot run on an imported G-buffer "
                                        "(--gbuffer import); use a screen-space kernel (have: " + screenSpaceAoNames() + ")");
    if (c.half && !supportsHalf(c.kernel))
        return badInput("--resolution half: kernel " + c.kernel + " has no half-resolution pipeline (use full)");
    // Values set in code (sweeps, matrices, tests) rather than parsed.
    for (const auto& [name, v] : c.params) {
        const auto* p = findParam(name);
        if (!p) return badInput("--" + name + ": unknown flag");
        CAVITY_TRY(kernels::checkValue(*p, v));
    }
    return {};
}

}  // namespace cavity
