// Loads the OpenImageIO module (image_module.h says why) and forwards the
// harness's image-file calls to it.
#include "images/image_module.h"

#include "core/progress.h"

#include "core/camera.h"
#include "images/gbuffer_import.h"
#include "images/image_io.h"

#include <dlfcn.h>

#include <filesystem>
#include <string>

namespace cavity::images {

namespace {

// The module's path in this build tree (CMakeLists.txt passes
// $<TARGET_FILE:cavity_image_module>), where every binary that loads it runs
// from; a `cavity` copied elsewhere with the module beside it finds that one
// first.
constexpr const char* kModulePath = CAVITY_IMAGE_MODULE_PATH;

std::string besideExecutable() {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return {};
    return (exe.parent_path() / std::filesystem::path(kModulePath).filename()).string();
}

Result<const ImageModule*> load() {
    // RTLD_LOCAL: OpenImageIO's symbols stay out of the binary's namespace.
    std::string path = besideExecutable();
    void* handle = path.empty() || !std::filesystem::exists(path) ? nullptr : ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        path = kModulePath;
        handle = ::dlopen(kModulePath, RTLD_NOW | RTLD_LOCAL);
    }
    if (!handle) return internal(std::string("load the image module: ") + ::dlerror());
    using Entry = const ImageModule* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, CAVITY_IMAGE_MODULE_ENTRY));
    if (!entry) return internal("load the image module " + path + ": no " + CAVITY_IMAGE_MODULE_ENTRY);
    return entry();   // never unloaded: OpenImageIO keeps threads and caches to exit
}

}  // namespace

Result<const ImageModule*> imageModule() {
    static const Result<const ImageModule*> module = load();
    return module;
}

Status writeImage(const std::string& path, const HostImage& img, Encoding enc, bool sixteenBit) {
    CAVITY_ASSIGN(const ImageModule* m, imageModule());
    return m->writeImage(path, img, enc, sixteenBit);
}

// Reads swap fd 2 (core::stderrLock()): one at a time, and never beside a
// progress line.
Result<HostImage> readImage(const std::string& path) {
    CAVITY_ASSIGN(const ImageModule* m, imageModule());
    std::lock_guard<std::mutex> hold(stderrLock());
    return m->readImage(path);
}

Result<GBufferImages> importGBuffer(const std::string& path, int width, int height) {
    CAVITY_ASSIGN(const ImageModule* m, imageModule());
    std::lock_guard<std::mutex> hold(stderrLock());
    return m->importGBuffer(path, width, height, &frameUniforms);
}

}  // namespace cavity::images