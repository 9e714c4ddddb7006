// The one axis expander: a configuration space given as lists, one list an
// axis, walked as their product. `cavity run`, `cavity quality`, the gate's
// matrices and the benchmark sweep all describe what they measure this way,
// so one order and one set of rules hold for all of them.
#pragma once

#include "plan/namespace.h"
#include "core/config.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace cavity::plan {

// Every list left empty keeps the base configuration's value on that axis.
// The product is walked with the first axis outermost, in this order:
// scene, kernel, parameters (in the order given), full/half, size, API,
// stage, G-buffer source.
struct Axes {
    std::vector<std::string> scenes;                                 // scene names (the "scene" parameter)
    std::vector<std::string> kernels;                                // AO kernel names
    std::vector<std::pair<std::string, std::vector<double>>> params;  // kernel parameters: samples, blur, radius...
    std::vector<bool> half;                                          // AO at half resolution
    std::vector<std::pair<int, int>> sizes;                          // width, height
    std::vector<gpu::Api> apis;
    std::vector<gpu::Stage> stages;
    std::vector<std::string> gbuffers;                               // "sdf", "raster" or "import"
    std::string gbufferFile;                                         // the capture, for "import"
};

// Calls visit with each configuration of the product, base's fields on every
// axis left empty. A visit that fails stops the walk with its error; so does
// a scene name that is not one.
using ConfigVisit = std::function<Status(RunConfig)>;
Status forEachConfig(const Axes& axes, const RunConfig& base, const ConfigVisit& visit);

// The product's configurations that the pipeline can run (a half-resolution
// configuration of a kernel that has none is left out), deduplicated by
// configuration id, in the walk's order.
Result<std::vector<RunConfig>> expandAxes(const Axes& axes, const RunConfig& base = {});

}  // namespace cavity::plan
