#include "plan/axes.h"

#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"

#include <set>

namespace cavity::plan {

namespace {

// One axis: how many points it has, and how point i sets a configuration.
struct Axis {
    size_t size;
    std::function<Status(RunConfig&, size_t)> set;
};

template <class T, class F>
void addAxis(std::vector<Axis>& out, const std::vector<T>& values, F setValue) {
    if (values.empty()) return;
    out.push_back({values.size(), [&values, setValue](RunConfig& c, size_t i) { return setValue(c, values[i]); }});
}

std::vector<Axis> axesOf(const Axes& a) {
    std::vector<Axis> out;
    addAxis(out, a.scenes, [](RunConfig& c, const std::string& s) { return setParam(c, "scene", s); });
    addAxis(out, a.kernels, [](RunConfig& c, const std::string& k) {
        c.kernel = k;
        return Status{};
    });
    for (const auto& [name, values] : a.params)
        addAxis(out, values, [&name](RunConfig& c, double v) {
            c.params[name] = v;
            return Status{};
        });
    addAxis(out, a.half, [](RunConfig& c, bool h) {
        c.half = h;
        return Status{};
    });
    addAxis(out, a.sizes, [](RunConfig& c, const std::pair<int, int>& wh) {
        std::tie(c.width, c.height) = wh;
        return Status{};
    });
    addAxis(out, a.apis, [](RunConfig& c, gpu::Api api) {
        c.api = api;
        return Status{};
    });
    addAxis(out, a.stages, [](RunConfig& c, gpu::Stage s) {
        c.stage = s;
        return Status{};
    });
    addAxis(out, a.gbuffers, [&a](RunConfig& c, const std::string& g) {
        c.raster = g == "raster";
        c.gbufferFile = g == "import" ? a.gbufferFile : std::string();
        return Status{};
    });
    return out;
}

Status walk(const std::vector<Axis>& axes, size_t depth, const RunConfig& c, const ConfigVisit& visit) {
    if (depth == axes.size()) return visit(c);
    for (size_t i = 0; i < axes[depth].size; ++i) {
        RunConfig next = c;
        CAVITY_TRY(axes[depth].set(next, i));
        CAVITY_TRY(walk(axes, depth + 1, next, visit));
    }
    return {};
}

}  // namespace

Status forEachConfig(const Axes& axes, const RunConfig& base, const ConfigVisit& visit) {
    return walk(axesOf(axes), 0, base, visit);
}

Result<std::vector<RunConfig>> expandAxes(const Axes& axes, const RunConfig& base) {
    std::vector<RunConfig> out;
    std::set<std::string> seen;
    std::vector<std::string> names;
    for (const auto& p : axes.params) names.push_back(p.first);
    CAVITY_TRY(forEachConfig(axes, base, [&](RunConfig c) {
        if (c.half && !supportsHalf(c.kernel)) return Status{};
        pipeline::dropUnreadParams(c, names);
        if (seen.insert(configId(c)).second) out.push_back(std::move(c));
        return Status{};
    }));
    return out;
}

}  // namespace cavity::plan
