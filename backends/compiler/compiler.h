// GLSL 4.50 -> SPIR-V through the glslang library, for either client API.
// Both backends compile the same expanded source (backend.h ShaderSource);
// only the client target differs (Vulkan 1.2 or OpenGL 4.5 SPIR-V).
#pragma once

#include "backend.h"

#include <cstdint>
#include <vector>

namespace cavity::kernels {

// On failure the message names the kernel, the source file and line of every
// diagnostic, e.g. "alchemy: kernels/ao/alchemy/ssao_alchemy.glsl:42: 'foo' : undeclared identifier".
Result<std::vector<uint32_t>> compileToSpirv(const gpu::ShaderSource& source, gpu::Api target);

// The uniforms the linked shader reads, by glslang's reflection: block
// members as "Block.member" ("Params.radius"), samplers by name ("in_normal").
// A member or sampler the code never reads is not among them, which is how
// `cavity kernels check` finds a declared parameter the shader ignores.
Result<std::vector<std::string>> activeUniforms(const gpu::ShaderSource& source, gpu::Api target);
// Rewrite "K:LINE" source-number references in a compiler or driver log into
// "files[K]:LINE", so that GL driver messages (GLSL fallback path) also name files.
std::string nameSourceLines(const std::string& log, const std::vector<std::string>& files);

}  // namespace cavity::kernels
