// Loads the OpenImageIO module (image_module.h says why) and forwards the
// harness's image-file calls to it.
#include "image_module.h"

#include "camera.h"
#include "gbuffer_import.h"
#include "image_io.h"

#include <dlfcn.h>

namespace cavity {

namespace {

// The module's path in this build tree, where every binary that loads it
// runs from (CMakeLists.txt passes $<TARGET_FILE:cavity_image_module>).
constexpr const char* kModulePath = CAVITY_IMAGE_MODULE_PATH;

Result<const ImageModule*> load() {
    // RTLD_LOCAL: OpenImageIO's symbols stay out of the binary's namespace.
    void* handle = ::dlopen(kModulePath, RTLD_NOW | RTLD_LOCAL);
    if (!handle) return internal(std::string("load the image module: ") + ::dlerror());
    using Entry = const ImageModule* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, CAVITY_IMAGE_MODULE_ENTRY));
    if (!entry)
        return internal(std::string("load the image module ") + kModulePath + ": no " + CAVITY_IMAGE_MODULE_ENTRY);
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

Result<HostImage> readImage(const std::string& path) {
    CAVITY_ASSIGN(const ImageModule* m, imageModule());
    return m->readImage(path);
}

Result<GBufferImages> importGBuffer(const std::string& path, int width, int height) {
    CAVITY_ASSIGN(const ImageModule* m, imageModule());
    return m->importGBuffer(path, width, height, &frameUniforms);
}

}  // namespace cavity
