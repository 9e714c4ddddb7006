// One run's configuration: the AO kernel, its parameters, size, stage and
// API. Its canonical id is built in config_id.h from the passes the
// configuration runs (pipeline.h), which is why neither the id nor the
// validation (pipeline.h) is declared here: this header stays below the
// pipeline.
#pragma once

#include "backend.h"
#include "core/image.h"
#include "kernel.h"

#include <memory>
#include <string>
#include <vector>

namespace cavity::core {

// A G-buffer made on the CPU and uploaded rather than rendered, in the
// formats and conventions gbuffer_sdf writes (kernels/passes/gbuffer_sdf/gbuffer_sdf.glsl):
// position RGBA (view x, y, z, linear depth -z), normal RGBA (view-space unit
// normal, 0), albedo RGBA (linear RGB, 1); all zero at background pixels.
// The chain adds the linear depth image gbuffer_sdf writes beside them (the
// position's w) when it uploads them.
struct GBufferImages {
    HostImage position, normal, albedo;
};

struct RunConfig {
    std::string kernel = "alchemy";       // the AO kernel (role "ao")
    kernels::ParamValues params;          // every kernel parameter given (samples, blur, scene, ...)
    int width = 320, height = 180;
    bool half = false;                    // AO at half resolution, bilateral upsample
    gpu::Stage stage = gpu::Stage::Compute;
    gpu::Api api = gpu::Api::Vulkan;
    bool raster = false;                  // rasterised G-buffer (harness/pipeline/meshes.cpp) instead of the ray march
    // Imported G-buffer: the capture's path (non-empty: import; the scene is
    // not used) and its images, loaded by the caller (runConfig loads them
    // when this is null). The pipeline has no "gbuffer" pass then.
    std::string gbufferFile;
    std::shared_ptr<const GBufferImages> gbufferImages;

    bool imported() const { return !gbufferFile.empty(); }
    std::string gbufferSource() const;    // "sdf", "raster" or "import"

    // A parameter's value: given, or the AO kernel's default where the
    // kernel declares it, or the declaration's.
    double param(const std::string& name) const;
    std::string scene() const;            // the name of params["scene"]
    int samples() const;
    int blur() const;
};

// The file stem of an imported capture as the id shows it (config_id.h):
// characters other than letters, digits, '.', '_' and '-' become '_'.
std::string importStem(const std::string& path);

// Parses "320x180"; the message names the flag.
Result<std::pair<int, int>> parseResolution(const std::string& flag, const std::string& text);
constexpr int kMaxResolution = 16384;

// Sets params[name] from a flag's text: numbers, or the name of an Enum choice.
// Unknown names and out-of-range values fail with a one-line message.
Status setParam(RunConfig& c, const std::string& name, const std::string& text);
// True when some kernel declares a parameter of this name.
bool isKernelParam(const std::string& name);

}  // namespace cavity::core