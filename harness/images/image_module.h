// The OpenImageIO half of the harness, a module loaded with dlopen on first
// use (harness/images/image_module.cpp). Linking OpenImageIO makes the loader map
// and relocate 261 shared libraries at every start, a delay `cavity --help`
// paid too (more under the sanitizers), and most starts read or write no
// image: --help, bad flags, `list`, `compare`, the tests' own processes.
//
// Everything that calls OpenImageIO is in the module (image_io.cpp,
// gbuffer_import.cpp, namespace cavity::oiio); the rest of
// the harness calls it through this table. The module is built with this
// build's compiler and flags, so the table passes C++ types as they are.
#pragma once

#include "images/namespace.h"
#include "core/config.h"
#include "core/image.h"
#include "images/image_io.h"
#include "kernel.h"
#include "result.h"

#include <string>

namespace cavity::images {

// The frame a G-buffer import rebuilds positions with (harness/core/camera.h):
// passed in, so that the module carries no harness code of its own.
using FrameFn = kernels::FrameUniforms (*)(int width, int height, int srcWidth, int srcHeight);

struct ImageModule {
    // image_io.h
    Status (*writeImage)(const std::string& path, const HostImage& img, Encoding enc, bool sixteenBit);
    Result<HostImage> (*readImage)(const std::string& path);
    // gbuffer_import.h
    Result<GBufferImages> (*importGBuffer)(const std::string& path, int width, int height, FrameFn frame);
};

// The module's one exported symbol.
#define CAVITY_IMAGE_MODULE_ENTRY "cavity_image_module"

// The module's side (namespace cavity::oiio, the functions of the table):
// defined only in the module, called only through the table.
namespace oiio {
Status writeImage(const std::string& path, const HostImage& img, Encoding enc, bool sixteenBit);
Result<HostImage> readImage(const std::string& path);
Result<GBufferImages> importGBuffer(const std::string& path, int width, int height, FrameFn frame);
}  // namespace oiio

// Loads the module on the first call (thread-safe) and keeps it loaded;
// an Internal error naming the file when it cannot be loaded.
Result<const ImageModule*> imageModule();

}  // namespace cavity::images