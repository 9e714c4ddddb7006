#include "gl/gl_debug.h"

#include "gl/gl_errors.h"

#include <utility>

namespace cavity::gpu::gl {
namespace {

const char* sourceName(GLenum source) {
    switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    }
    return "other";
}

const char* typeName(GLenum type) {
    switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behavior";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    }
    return "other";
}

const char* severityName(GLenum severity) {
    switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH: return "high";
    case GL_DEBUG_SEVERITY_MEDIUM: return "medium";
    case GL_DEBUG_SEVERITY_LOW: return "low";
    }
    return "notification";
}

}  // namespace

Status DebugLog::install() {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    glDebugMessageCallback(&DebugLog::onMessage, this);
    installed_ = true;
    return checkGl("enable KHR_debug output");
}

void DebugLog::uninstall() {
    if (!installed_) return;
    glDebugMessageCallback(nullptr, nullptr);
    glDisable(GL_DEBUG_OUTPUT);
    installed_ = false;
}

std::vector<std::string> DebugLog::take() { return std::exchange(messages_, {}); }

void GLAPIENTRY DebugLog::onMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                    const GLchar* message, const void* self) {
    auto& log = *static_cast<DebugLog*>(const_cast<void*>(self));
    if (log.muted_ > 0) return;
    if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
    const std::string text = length < 0 ? std::string(message) : std::string(message, size_t(length));
    log.messages_.push_back(std::string("gl debug ") + typeName(type) + " (" + severityName(severity) + ", " +
                            sourceName(source) + ", id " + std::to_string(id) + "): " + oneLine(text));
}

}  // namespace cavity::gpu::gl
