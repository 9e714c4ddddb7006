// How PassChain records a frame (pipeline.h): a timestamp scope a pass
// (record), or one around every pass but the G-buffer (recordInOneScope).
// A timestamp pair around each pass costs GL several microseconds more than
// Vulkan, the larger part of GL's per-pass gap (study
// 2026-12-06_gpu_packed_texel): one scope is the pipeline as an engine that
// times only the whole runs it.
#include "pipeline/pipeline.h"

namespace cavity::pipeline {

void PassChain::recordFrame(bool oneScope) {
    bool open = false;
    for (size_t i = 0; i < passes_.size(); ++i) {
        // A backend records the barrier at the next pass, inside its scope;
        // the scope's begin timestamp is taken once every earlier command has
        // finished (BOTTOM_OF_PIPE, GL_TIMESTAMP), so it still follows the
        // completion of the pass before.
        if (i) gpu_.barrier();
        const bool own = !oneScope || specs_[i].name == "gbuffer";
        if (!own && !open) {
            gpu_.beginScope("pipeline");
            open = true;
        }
        recordPass(i, own);
    }
    if (open) gpu_.endScope();
}

void PassChain::record() { recordFrame(false); }

void PassChain::recordInOneScope() { recordFrame(true); }

}  // namespace cavity::pipeline
