#include "measure/quality.h"

#include "core/config.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cmath>

namespace cavity::measure {

namespace {

RunConfig baseConfig(gpu::Backend& gpu, const std::string& kernel, int width, int height) {
    RunConfig c;
    c.api = gpu.api();
    c.kernel = kernel;
    c.width = width;
    c.height = height;
    c.params["blur"] = 0;
    return c;
}

}  // namespace

Result<GroundTruth> groundTruth(gpu::Backend& gpu, const std::string& scene, int width, int height, int rays,
                                double radius) {
    RunConfig c = baseConfig(gpu, "ground_truth", width, height);
    CAVITY_TRY(setParam(c, "scene", scene));
    c.params["rays"] = rays;
    if (radius > 0) c.params["radius"] = radius;
    CAVITY_ASSIGN(auto images, renderImages(gpu, c, {"ao", "position"}));
    GroundTruth t;
    t.ao = std::move(images["ao"]);
    const HostImage& position = images["position"];
    t.surface = HostImage(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) t.surface.at(x, y) = position.at(x, y, 3) > 0.0f ? 1.0f : 0.0f;
    return t;
}

QualityRow compareToTruth(const HostImage& ao, const GroundTruth& truth) {
    QualityRow r;
    double sum = 0, sumAo = 0, sumTruth = 0;
    for (int y = 0; y < truth.ao.height; ++y)
        for (int x = 0; x < truth.ao.width; ++x) {
            if (truth.surface.at(x, y) == 0.0f) continue;
            const double a = ao.at(x, y, 0), t = truth.ao.at(x, y, 0);
            const double e = std::fabs(a - t);
            sum += e;
            sumAo += a;
            sumTruth += t;
            r.maxAbsError = std::max(r.maxAbsError, e);
            ++r.pixels;
        }
    if (r.pixels) {
        r.meanAbsError = sum / double(r.pixels);
        r.meanAo = sumAo / double(r.pixels);
        r.meanTruth = sumTruth / double(r.pixels);
    }
    return r;
}

void applySwitches(RunConfig& c, const kernels::ParamValues& switches) {
    const auto* k = kernels::find(c.kernel);
    for (const auto& [name, value] : switches)
        if (k && kernels::declares(*k, name)) c.params[name] = value;
}

Result<std::vector<QualityRow>> measureQuality(gpu::Backend& gpu, const QualityOptions& o) {
    std::vector<std::string> names = o.kernels;
    if (names.empty())
        for (const auto& k : kernels::all())
            if (k.role == kernels::Role::Ao) names.push_back(k.name);
    std::vector<QualityRow> rows;
    for (const auto& scene : o.scenes) {
        CAVITY_ASSIGN(const GroundTruth truth, groundTruth(gpu, scene, o.width, o.height, o.rays, o.sharedReach ? o.radius : 0));
        for (const auto& kernel : names)
            for (int n : o.samples) {
                RunConfig c = baseConfig(gpu, kernel, o.width, o.height);
                CAVITY_TRY(setParam(c, "scene", scene));
                c.params["samples"] = n;
                c.params["blur"] = o.blur;
                if (o.sharedReach) c.params["radius"] = o.radius;
                c.half = o.half && supportsHalf(kernel);
                c.stage = o.stage;
                applySwitches(c, o.switches);
                CAVITY_ASSIGN(auto images, renderImages(gpu, c, {"ao_blur"}, o.overrides));
                QualityRow r = compareToTruth(images["ao_blur"], truth);
                r.scene = scene;
                r.kernel = kernel;
                r.samples = n;
                rows.push_back(r);
            }
    }
    return rows;
}

}  // namespace cavity::measure