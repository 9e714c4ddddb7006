#include "pipeline/config_id.h"

#include "pipeline/pipeline.h"

#include <algorithm>
#include <charconv>

namespace cavity::pipeline {

namespace {

// A parameter value as the id writes it: the shortest text that reads back
// as the same double (0.3, not 0.29999999999999999), or an Enum's choice name.
std::string valueText(const std::string& name, double v) {
    const auto* p = kernels::findParam(name);
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
    auto declares = [&](const std::string& name) { return k && kernels::declares(*k, name); };
    std::string count = "n";
    count += std::to_string(c.samples());
    std::string countParam = "samples";
    if (!declares("samples") && declares("rays")) {
        countParam = "rays";
        count = "rays";
        count += valueText("rays", c.param("rays"));
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

}  // namespace cavity::pipeline