// PassChain::recordInOneScope (pipeline.h): the frame record() makes, with
// one timestamp scope around every pass but the G-buffer. A timestamp pair
// around each pass costs GL several microseconds more than Vulkan, the
// larger part of GL's per-pass gap (study 2026-12-06_gpu_packed_texel):
// this is the pipeline as an engine that times only the whole runs it.
#include "pipeline/pipeline.h"

namespace cavity::pipeline {

void PassChain::recordInOneScope() {
    bool open = false;
    for (size_t i = 0; i < passes_.size(); ++i) {
        if (i) gpu_.barrier();
        const bool gbuffer = specs_[i].name == "gbuffer";
        if (!gbuffer && !open) {
            gpu_.beginScope("pipeline");
            open = true;
        }
        recordPass(i, gbuffer);
    }
    if (open) gpu_.endScope();
}

}  // namespace cavity::pipeline
