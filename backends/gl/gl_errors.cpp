#include "gl/gl_errors.h"

namespace cavity::gpu::gl {

const char* glErrorName(GLenum error) {
    switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    }
    return "unknown GL error";
}

Status checkGl(const std::string& what) {
    const GLenum first = glGetError();
    if (first == GL_NO_ERROR) return Status::success();
    // GL keeps one flag per error kind; clear them all so that the next
    // check reports only its own call. A lost context keeps reporting, so bound it.
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {}
    return internal("gl: " + what + ": " + glErrorName(first));
}

std::string oneLine(const std::string& text) {
    std::string out;
    bool pendingBreak = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pendingBreak = !out.empty();
            continue;
        }
        if (pendingBreak) out += "; ";
        pendingBreak = false;
        out += c;
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
    return out;
}

}  // namespace cavity::gpu::gl
