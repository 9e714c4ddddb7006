// Shader programs from backend.h ShaderSources: the shared SPIR-V through
// GL_ARB_gl_spirv first, the same GLSL text through the driver's compiler
// when that path is unavailable or fails for a kernel. All stages of one
// program take the same path.
#pragma once

#include "backend.h"

#include <epoxy/gl.h>

#include <span>
#include <string>

namespace cavity::gpu::gl {

struct BuiltProgram {
    GLuint program = 0;
    PipelineInfo info;
};

// spirvUnusable: why SPIR-V is not even tried ("driver lacks GL_ARB_gl_spirv",
// "CAVITY_GL_FORCE_GLSL=1"), or empty to try it. A GLSL failure comes back as
// "gl: compile <name>: <driver log with kernel file names>".
Result<BuiltProgram> buildProgram(std::span<const ShaderSource* const> stages, const std::string& spirvUnusable);

}  // namespace cavity::gpu::gl
