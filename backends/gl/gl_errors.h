// GL error flags turned into values, so that every GL call site can say what
// it attempted ("gl: glTextureStorage2D 320x180 RGBA16F 'ao': GL_INVALID_VALUE").
#pragma once

#include "result.h"

#include <epoxy/gl.h>

#include <string>

namespace cavity::gpu::gl {

const char* glErrorName(GLenum error);

// Drains every raised GL error flag; the first becomes "gl: <what>: GL_...".
Status checkGl(const std::string& what);

// Driver logs span lines; error messages and fallback reasons are one line.
std::string oneLine(const std::string& text);

}  // namespace cavity::gpu::gl
