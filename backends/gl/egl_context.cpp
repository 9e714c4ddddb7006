#include "gl/egl_context.h"

#include <map>
#include <mutex>
#include <sstream>
#include <vector>

namespace cavity::gpu::gl {
namespace {

const char* eglErrorName(EGLint error) {
    switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT: return "EGL_BAD_DEVICE_EXT";
    }
    return "unknown EGL error";
}

Error eglFailure(const std::string& what) { return internal(what + ": " + eglErrorName(eglGetError())); }

bool hasWord(const char* list, const std::string& word) {
    if (!list) return false;
    std::istringstream words(list);
    for (std::string w; words >> w;)
        if (w == word) return true;
    return false;
}

Status needClientExtensions(std::initializer_list<const char*> names) {
    for (const char* name : names)
        if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, name)) return internal(std::string("no ") + name);
    return {};
}

// EGL keeps one EGLDisplay per platform and native display, so two backends on
// one device share it, and eglTerminate from one would pull it from under the
// other. Count our initialisations and terminate with the last.
std::mutex displayMutex;
std::map<EGLDisplay, int> displayRefs;

Status initializeDisplay(EGLDisplay display) {
    std::lock_guard lock(displayMutex);
    int& refs = displayRefs[display];
    if (refs == 0) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            displayRefs.erase(display);
            return eglFailure("eglInitialize");
        }
    }
    ++refs;
    return {};
}

void releaseDisplay(EGLDisplay display) {
    std::lock_guard lock(displayMutex);
    auto it = displayRefs.find(display);
    if (it == displayRefs.end() || --it->second > 0) return;
    displayRefs.erase(it);
    eglTerminate(display);
}

struct NamedDisplay {
    EGLDisplay display;
    std::string name;
};

// The core eglGetPlatformDisplay is not used: libepoxy only offers it once a
// display reports EGL 1.5, and there is no display yet. The EXT entry point
// takes the same arguments on every driver that has the platforms below.
Result<NamedDisplay> deviceDisplay(int index) {
    CAVITY_TRY(needClientExtensions({"EGL_EXT_platform_base", "EGL_EXT_device_enumeration", "EGL_EXT_platform_device"}));
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count)) return eglFailure("eglQueryDevicesEXT");
    if (count == 0) return internal("no devices");
    if (index < 0 || index >= count)
        return internal("device index " + std::to_string(index) + " out of range, " + std::to_string(count) + " devices");
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
    if (!eglQueryDevicesEXT(count, devices.data(), &count)) return eglFailure("eglQueryDevicesEXT");
    const EGLDeviceEXT device = devices[size_t(index)];
    const EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display == EGL_NO_DISPLAY)
        return eglFailure("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device " + std::to_string(index) + ")");

    // With several GPUs the DRM node says which one this index picked.
    std::string name = "EGL device " + std::to_string(index);
    const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
    const char* node = hasWord(extensions, "EGL_EXT_device_drm") ? eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT) : nullptr;
    if (node) name += std::string(", ") + node;
    else if (hasWord(extensions, "EGL_MESA_device_software")) name += ", software";
    return NamedDisplay{display, name};
}

Result<NamedDisplay> surfacelessDisplay() {
    CAVITY_TRY(needClientExtensions({"EGL_EXT_platform_base", "EGL_MESA_platform_surfaceless"}));
    const EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) return eglFailure("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
    return NamedDisplay{display, "EGL surfaceless"};
}

// An OpenGL 4.5 core context on an initialised display, current on this
// thread without a surface: the harness only renders into textures.
Result<EGLContext> createContext(EGLDisplay display, bool debug) {
    for (const char* name : {"EGL_KHR_create_context", "EGL_KHR_surfaceless_context"})
        if (!epoxy_has_egl_extension(display, name)) return internal(std::string("no ") + name);
    if (!eglBindAPI(EGL_OPENGL_API)) return eglFailure("eglBindAPI(EGL_OPENGL_API)");

    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
        // A surface type mask of 0 matches every config, pbuffer-only ones included.
        const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
        EGLint found = 0;
        if (!eglChooseConfig(display, want, &config, 1, &found)) return eglFailure("eglChooseConfig(EGL_OPENGL_BIT)");
        if (found == 0) return internal("no EGL config renders OpenGL");
    }
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION_KHR, 4,
        EGL_CONTEXT_MINOR_VERSION_KHR, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
        EGL_CONTEXT_FLAGS_KHR, debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
        EGL_NONE};
    const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT)
        return eglFailure(std::string("eglCreateContext OpenGL 4.5 core") + (debug ? " debug" : ""));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        Error e = eglFailure("eglMakeCurrent without surface");
        eglDestroyContext(display, context);
        return e;
    }
    return context;
}

Result<std::unique_ptr<EglContext>> start(Result<NamedDisplay> opened, bool debug) {
    if (!opened) return opened.error();
    const EGLDisplay display = opened->display;
    CAVITY_TRY(initializeDisplay(display));
    auto context = createContext(display, debug);
    if (!context) {
        releaseDisplay(display);
        return context.error();
    }
    return std::make_unique<EglContext>(display, *context, opened->name);
}

}  // namespace

Result<std::unique_ptr<EglContext>> EglContext::create(int deviceIndex, bool debugContext) {
    auto device = start(deviceDisplay(deviceIndex), debugContext);
    if (device) return device;
    // Surfaceless has one device: asked for another, running there would
    // time a GPU the user did not ask for.
    if (deviceIndex != 0)
        return unavailable("gl: --device " + std::to_string(deviceIndex) + ": no such EGL device (" +
                           device.error().message + ")");
    auto surfaceless = start(surfacelessDisplay(), debugContext);
    if (surfaceless) return surfaceless;
    return unavailable("gl: could not start: tried EGL device platform (" + device.error().message +
                       "), EGL_MESA_platform_surfaceless (" + surfaceless.error().message + ")");
}

EglContext::EglContext(EGLDisplay display, EGLContext context, std::string platform)
    : display_(display), context_(context), platform_(std::move(platform)) {}

EglContext::~EglContext() {
    if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    releaseDisplay(display_);
}

Status EglContext::makeCurrent() {
    if (eglGetCurrentContext() == context_) return {};
    // The bound client API is per thread, and so is the current-context lookup.
    if (!eglBindAPI(EGL_OPENGL_API)) return eglFailure("gl: eglBindAPI(EGL_OPENGL_API)");
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return eglFailure("gl: eglMakeCurrent");
    return {};
}

}  // namespace cavity::gpu::gl
