// Runs a single kernel on host images: the inputs are uploaded, the kernel
// dispatched (or drawn) once, the outputs read back. For tests and for
// checking one pass of a chain against its CPU reference.
#pragma once

#include "pipeline/namespace.h"
#include "backend.h"
#include "core/image.h"
#include "kernel.h"

#include <map>
#include <string>
#include <vector>

namespace cavity::pipeline {

struct KernelRun {
    const kernels::KernelDecl* kernel = nullptr;
    kernels::ParamValues params;         // missing ones take their defaults
    gpu::Stage stage = gpu::Stage::Compute;
    int width = 0, height = 0;           // output size
    int srcWidth = 0, srcHeight = 0;     // the camera's image size (0: same as output)
    std::vector<const HostImage*> inputs;   // in kernel.inputs order
    std::vector<gpu::Format> inputFormats;  // empty: RGBA32F / RG16F... by channel count at 32-bit float
    std::map<std::string, std::string> overrides;
};

Result<std::vector<HostImage>> runKernel(gpu::Backend& gpu, const KernelRun& run);

// Rounds every value as storing it in `format` would (half floats, 8-bit unorm).
void quantize(HostImage& img, gpu::Format format);

}  // namespace cavity::pipeline