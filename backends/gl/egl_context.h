// A headless OpenGL 4.5 core context through EGL, with no surface: the EGL
// device platform first (it picks a GPU by index), then Mesa's surfaceless
// platform. Every entry point comes through libepoxy.
#pragma once

#include "result.h"

#include <epoxy/egl.h>

#include <memory>
#include <string>

namespace cavity::gpu::gl {

class EglContext {
public:
    // Fails with BackendUnavailable naming each platform tried and why it failed.
    static Result<std::unique_ptr<EglContext>> create(int deviceIndex, bool debugContext);
    EglContext(EGLDisplay display, EGLContext context, std::string platform);
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    // Makes the context current on the calling thread; cheap when it already is.
    Status makeCurrent();
    // "EGL device 0 (/dev/dri/renderD128)" or "EGL surfaceless", for DeviceInfo.
    const std::string& platform() const { return platform_; }

private:
    EGLDisplay display_;
    EGLContext context_;
    std::string platform_;
};

}  // namespace cavity::gpu::gl
