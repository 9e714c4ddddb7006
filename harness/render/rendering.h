// Rendering a matrix: the half of the gate that needs a GPU. cavity_render
// stores each Rendering in a render folder (render_folder.h); `cavity gate`
// judges each one in memory as it comes (harness/gate/gate.h). Both get their
// Renderings from renderEntries, so the two paths judge the same pixels.
#pragma once

#include "render/namespace.h"
#include "backend.h"
#include "core/config.h"
#include "core/image.h"
#include "plan/matrix.h"
#include "pipeline/pipeline.h"
#include "measure/timing.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <optional>
#include <cmath>
#include <string>
#include <vector>

namespace cavity::render {

struct PassTime {
    std::string pass;
    double medianMs = 0;
    std::string clock;            // Timing::clock: "gpu-timestamp" or "wall"
    // The median's distribution-free 95% interval over the frames
    // (measure::medianNoise); NaN where the frames are too few for one.
    double lowMs = NAN, highMs = NAN;
    std::vector<gpu::ShaderStat> shaderStats;   // the driver's, of the pass's pipeline (PipelineInfo::stats)
};

// An image judged where it was rendered (cavity_render --store): against
// the nearest image approved for the device's class, from the image store,
// with the gate's own code and tolerances. Only a failing one is written to
// the folder; a passing one travels as this record.
struct RemoteCheck {
    std::string reference;        // "<class> <api>/<stage>"
    std::string referenceDigest;  // the approved image's digest
    bool passed = false;
    std::vector<std::string> failures;
    nlohmann::json metrics;       // as gate.json writes them
    nlohmann::json tolerance;     // the tolerance judged with, as gate.json writes it
};

// One repetition of one matrix entry.
struct Rendering {
    size_t index = 0;             // in Matrix::expand()
    int repetition = 0;
    RunConfig config;
    std::string id, key;          // configId, plan::baselineKey
    gpu::DeviceInfo device;       // deviceName empty when the backend did not start
    std::string error;            // the configuration did not run: why
    int errorCode = 0;            // and its ErrorCode
    bool deterministic = true;    // a second frame gave the same bits
    std::vector<PassTime> timings;
    // The checked images (plan::checkedImages()) by name: their digests
    // always, their pixels where the consumer holds them (a judge reading a
    // later repetition that matches repetition 0 has only the digest).
    std::map<std::string, std::string> digests;
    std::map<std::string, HostImage> images;
    // Read back from a render folder: images judged where they were rendered
    // (render_manifest.h RemoteCheck), by name.
    std::map<std::string, RemoteCheck> judged;
};

struct BackendFailure {
    gpu::Api api;
    int repetition = 0;
    std::string message;
};

struct RenderOptions {
    std::vector<gpu::Api> apis{gpu::Api::OpenGL, gpu::Api::Vulkan};
    int device = 0;
    bool validation = false;
    int repeat = 1;               // render the whole selection this many times
    SourceOverrides overrides;    // planted-bug tests
    // Timing (harness/measure/timing.h); unset: the device's default. `--max-noise 0`
    // measures exactly the matrix's frames, which keeps a 70-configuration
    // render of 160x90 images to seconds on a GPU.
    std::optional<TimingMode> mode;
    std::optional<double> maxNoise, maxSeconds;
    int views = 1;                // camera views measured in turn (measure::RunOptions::views)
};

using RenderSink = std::function<Status(Rendering&&)>;

// Renders `entries` `repeat` times over, each time API by API (OpenGL first,
// the order the gate has always used) on a backend started for it, and
// hands every Rendering to `sink` as soon as it exists, so that one
// configuration's images are held at a time. A backend that does not start
// gives each of its entries a Rendering with errorCode 3 and is listed in
// *failures; a configuration that fails gives a Rendering with its error.
// Only an error returned by `sink` stops the run.
Status renderEntries(const plan::Matrix& m, const std::vector<plan::MatrixEntry>& entries, const RenderOptions& o,
                     const RenderSink& sink, std::vector<BackendFailure>* failures);

}  // namespace cavity::render
