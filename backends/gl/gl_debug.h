// KHR_debug output collected for takeDebugMessages(): errors, and anything
// else the driver rates high severity. Output is synchronous, so a message
// arrives inside the call that caused it, on the calling thread.
#pragma once

#include "result.h"

#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace cavity::gpu::gl {

class DebugLog {
public:
    DebugLog() = default;
    DebugLog(const DebugLog&) = delete;
    DebugLog& operator=(const DebugLog&) = delete;

    // Needs the context current; stays installed until uninstall().
    Status install();
    void uninstall();
    std::vector<std::string> take();

    // Drops messages while alive. Shader builds report their failures as
    // values; the SPIR-V attempt may fail by design before the GLSL fallback.
    class Mute {
    public:
        explicit Mute(DebugLog& log) : log_(log) { ++log_.muted_; }
        ~Mute() { --log_.muted_; }
        Mute(const Mute&) = delete;
        Mute& operator=(const Mute&) = delete;
    private:
        DebugLog& log_;
    };

private:
    static void GLAPIENTRY onMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                     const GLchar* message, const void* self);
    std::vector<std::string> messages_;
    int muted_ = 0;
    bool installed_ = false;
};

}  // namespace cavity::gpu::gl
