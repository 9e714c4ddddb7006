// cavity_render carries no OpenImageIO, but it shares harness/measure/runner.cpp with
// cavity, and runConfig reaches image files in two places: writing images
// when RunOptions::outDir is set, and reading a capture for an imported
// G-buffer. cavity_render asks for neither (it keeps pixels in memory, and a
// matrix has no imported G-buffer), so here both are errors, as values.
#include "images/gbuffer_import.h"
#include "images/image_io.h"

namespace cavity::images {

Status writeImage(const std::string& path, const HostImage&, Encoding, bool) {
    return badInput(path + ": cavity_render writes no EXR or PNG files (no OpenImageIO); use cavity run");
}

// With --store, cavity_render judges against images approved for its device
// class, which come from the image store in the render-folder format; a
// baseline file (EXR, PNG) is for the judge at home.
Result<HostImage> readImage(const std::string& path) {
    return badInput(path + ": cavity_render reads no EXR or PNG files (no OpenImageIO); judge with cavity gate judge");
}

Result<GBufferImages> importGBuffer(const std::string& path, int, int) {
    return badInput("--gbuffer-file " + path + ": cavity_render imports no G-buffers (no OpenImageIO); use cavity run");
}

}  // namespace cavity::images
