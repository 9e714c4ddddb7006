#include "render/rendering.h"

#include "pipeline/config_id.h"
#include "core/digest.h"
#include "measure/runner.h"

#include <algorithm>

namespace cavity::render {

namespace {

Rendering start(const plan::MatrixEntry& e, int repetition) {
    Rendering r;
    r.index = e.index;
    r.repetition = repetition;
    r.config = e.config;
    r.id = configId(e.config);
    r.key = plan::baselineKey(e.config);
    return r;
}

}  // namespace

Status renderEntries(const plan::Matrix& m, const std::vector<plan::MatrixEntry>& entries, const RenderOptions& o,
                     const RenderSink& sink, std::vector<BackendFailure>* failures) {
    // A bad CAVITY_*_BARRIERS is the user's input, not a backend that failed.
    if (auto env = gpu::withEnvironment({}); !env) return env.error();
    for (int rep = 0; rep < o.repeat; ++rep)
        for (auto api : {gpu::Api::OpenGL, gpu::Api::Vulkan}) {
            std::vector<const plan::MatrixEntry*> mine;
            for (const auto& e : entries)
                if (e.config.api == api) mine.push_back(&e);
            if (mine.empty() || std::find(o.apis.begin(), o.apis.end(), api) == o.apis.end()) continue;
            gpu::BackendOptions bo;
            bo.deviceIndex = o.device;
            bo.validation = o.validation;
            auto backend = gpu::createBackend(api, bo);
            if (!backend) {
                if (failures) failures->push_back({api, rep, backend.error().message});
                for (const auto* e : mine) {
                    Rendering r = start(*e, rep);
                    r.error = backend.error().message;
                    r.errorCode = int(ErrorCode::BackendUnavailable);
                    CAVITY_TRY(sink(std::move(r)));
                }
                continue;
            }
            gpu::Backend& gpu = **backend;
            for (const auto* e : mine) {
                Rendering r = start(*e, rep);
                r.device = gpu.info();
                RunOptions ro;
                ro.frames = m.frames;
                ro.warmup = m.warmup;
                ro.keepImages = true;
                ro.checkDeterminism = true;
                ro.overrides = o.overrides;
                ro.mode = o.mode;
                ro.maxNoise = o.maxNoise;
                ro.maxSeconds = o.maxSeconds;
                ro.views = o.views;
                auto rec = runConfig(gpu, e->config, ro);
                if (!rec) {
                    r.error = rec.error().message;
                    r.errorCode = int(rec.error().code);
                } else if (!rec->nonFinite.empty()) {
                    // A NaN anywhere fails the configuration, whatever its
                    // checked images show (an 8-bit composite clamps it away).
                    for (const auto& n : rec->nonFinite) r.error += (r.error.empty() ? "" : "; ") + n.message();
                    r.errorCode = int(ErrorCode::CheckFailed);
                } else {
                    r.deterministic = rec->deterministic;
                    for (const auto& p : rec->timing.passes) {
                        const double half = measure::medianNoise(p.ms) * p.stats.median;
                        const auto info = rec->pipelines.find(p.name);
                        r.timings.push_back({p.name, p.stats.median, rec->timing.clock,
                                             std::isfinite(half) ? p.stats.median - half : NAN,
                                             std::isfinite(half) ? p.stats.median + half : NAN,
                                             info == rec->pipelines.end() ? std::vector<gpu::ShaderStat>{} : info->second.stats});
                    }
                    for (const auto& ci : plan::checkedImages()) {
                        HostImage& img = rec->pixels.at(ci.name);
                        r.digests[ci.name] = imageDigest(img);
                        r.images[ci.name] = std::move(img);
                    }
                }
                CAVITY_TRY(sink(std::move(r)));
            }
        }
    return {};
}

}  // namespace cavity::render
