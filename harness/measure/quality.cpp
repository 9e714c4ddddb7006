#include "measure/quality.h"

#include "core/config.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

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

namespace {

using Tiles = std::vector<std::pair<double, long long>>;

// The kIntervalLow and kIntervalHigh quantiles of a statistic of the tiles
// over resamples of whole tile indices, from a fixed seed: the same images
// give the same interval. `stat` gets each resample's (summed error, pixels) of
// every tile list given.
template <class Stat>
std::pair<double, double> bootstrap(const std::vector<const Tiles*>& lists, Stat stat) {
    const size_t count = lists.front()->size();
    if (count == 0) return {0, 0};
    std::mt19937_64 rng(0x5eed);
    std::uniform_int_distribution<size_t> pick(0, count - 1);
    std::vector<double> draws;
    draws.reserve(kBootstrapDraws);
    std::vector<std::pair<double, long long>> sums(lists.size());
    for (int d = 0; d < kBootstrapDraws; ++d) {
        std::fill(sums.begin(), sums.end(), std::pair<double, long long>{0, 0});
        for (size_t k = 0; k < count; ++k) {
            const size_t i = pick(rng);
            for (size_t l = 0; l < lists.size(); ++l) {
                sums[l].first += (*lists[l])[i].first;
                sums[l].second += (*lists[l])[i].second;
            }
        }
        draws.push_back(stat(sums));
    }
    std::sort(draws.begin(), draws.end());
    return {draws[size_t(kIntervalLow * double(draws.size() - 1))], draws[size_t(kIntervalHigh * double(draws.size() - 1))]};
}

double mae(const std::pair<double, long long>& s) { return s.second ? s.first / double(s.second) : 0; }

}  // namespace

QualityRow compareToTruth(const HostImage& ao, const GroundTruth& truth) {
    QualityRow r;
    double sum = 0, sumAo = 0, sumTruth = 0;
    const int tilesX = (truth.ao.width + kTileSide - 1) / kTileSide;
    Tiles tiles(size_t(tilesX) * ((truth.ao.height + kTileSide - 1) / kTileSide));
    for (int y = 0; y < truth.ao.height; ++y)
        for (int x = 0; x < truth.ao.width; ++x) {
            if (truth.surface.at(x, y) == 0.0f) continue;
            const double a = ao.at(x, y, 0), t = truth.ao.at(x, y, 0);
            const double e = std::fabs(a - t);
            auto& tile = tiles[size_t(y / kTileSide) * tilesX + x / kTileSide];
            tile.first += e;
            ++tile.second;
            sum += e;
            sumAo += a;
            sumTruth += t;
            // A NaN pixel makes the largest error NaN: std::max would pass
            // it over and report the largest finite one.
            r.maxAbsError = std::isnan(e) || std::isnan(r.maxAbsError) ? e + r.maxAbsError : std::max(r.maxAbsError, e);
            ++r.pixels;
        }
    if (r.pixels) {
        r.meanAbsError = sum / double(r.pixels);
        r.meanAo = sumAo / double(r.pixels);
        r.meanTruth = sumTruth / double(r.pixels);
    }
    r.tiles = std::move(tiles);
    std::tie(r.maeLow, r.maeHigh) = bootstrap({&r.tiles}, [](const auto& s) { return mae(s[0]); });
    return r;
}

std::pair<double, double> maeDifference(const QualityRow& a, const QualityRow& b) {
    if (a.tiles.size() != b.tiles.size()) return {-1, 1};   // not comparable: nothing can be told apart
    return bootstrap({&a.tiles, &b.tiles}, [](const auto& s) { return mae(s[1]) - mae(s[0]); });
}

void applySwitches(RunConfig& c, const kernels::ParamValues& switches) {
    const auto* k = kernels::find(c.kernel);
    for (const auto& [name, value] : switches)
        if (k && kernels::declares(*k, name)) c.params[name] = value;
}

Status checkSwitchesUsed(const kernels::ParamValues& switches, const std::vector<RunConfig>& measured) {
    for (const auto& [name, value] : switches)
        if (!measured.empty() && std::none_of(measured.begin(), measured.end(), [&](const RunConfig& c) {
                const auto* k = kernels::find(c.kernel);
                return k && kernels::declares(*k, name);
            }))
            return badInput("--" + name + ": no kernel measured declares it (set it on one that does, with --kernel)");
    return {};
}

Result<std::vector<QualityRow>> measureQuality(gpu::Backend& gpu, const QualityOptions& o) {
    std::vector<std::string> names = o.kernels;
    if (names.empty())
        for (const auto& k : kernels::all())
            if (k.role == kernels::Role::Ao) names.push_back(k.name);
    std::vector<QualityRow> rows;
    for (const auto& scene : o.scenes) {
        CAVITY_ASSIGN(GroundTruth made, groundTruth(gpu, scene, o.width, o.height, o.rays, o.sharedReach ? o.radius : 0));
        const auto truth = std::make_shared<const GroundTruth>(std::move(made));
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
                QualityRow r = compareToTruth(images["ao_blur"], *truth);
                r.scene = scene;
                r.kernel = kernel;
                r.samples = n;
                if (o.keepImages) {
                    r.ao = std::make_shared<const HostImage>(std::move(images["ao_blur"]));
                    r.truth = truth;
                }
                rows.push_back(r);
            }
    }
    return rows;
}

}  // namespace cavity::measure