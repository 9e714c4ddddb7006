// One GL sampler object per SamplerState (there are eight), created on first
// use. Samplers override the texture's own parameters at their unit.
#pragma once

#include "backend.h"

#include <epoxy/gl.h>

#include <array>

namespace cavity::gpu::gl {

class SamplerCache {
public:
    Result<GLuint> get(const SamplerState& state);
    void release();   // needs the context current; otherwise the samplers die with it

private:
    std::array<GLuint, 8> samplers_{};
};

}  // namespace cavity::gpu::gl
