#include "image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

namespace cavity {

namespace fs = std::filesystem;
using namespace OIIO;

Status writeImage(const std::string& path, const HostImage& img, Encoding enc, bool sixteenBit) {
    const std::string ext = fs::path(path).extension().string();
    const bool exr = ext == ".exr";
    if (!exr && ext != ".png") return badInput(path + ": unsupported image extension (use .exr or .png)");
    int channels = img.channels;
    if (!exr && channels == 2) channels = 3;
    ImageSpec spec(img.width, img.height, channels, exr ? TypeDesc::HALF : (sixteenBit ? TypeDesc::UINT16 : TypeDesc::UINT8));
    if (exr) spec.attribute("compression", "zip");
    std::vector<float> px(size_t(img.width) * img.height * channels, 0.0f);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
        for (int c = 0; c < img.channels; ++c) {
            float v = img.pixels[p * img.channels + c];
            if (!exr) {
                if (enc == Encoding::SignedUnit) v = 0.5f * v + 0.5f;
                v = std::clamp(v, 0.0f, 1.0f);
            }
            px[p * channels + c] = v;
        }
    // Keep the real extension last so OpenImageIO picks the writer.
    const fs::path target(path);
    const fs::path tmp = target.parent_path() / (target.stem().string() + ".tmp-" + std::to_string(::getpid()) + ext);
    auto out = ImageOutput::create(tmp.string());
    if (!out) return internal("write " + path + ": " + OIIO::geterror());
    if (!out->open(tmp.string(), spec) || !out->write_image(TypeDesc::FLOAT, px.data()) || !out->close()) {
        const std::string err = out->geterror();
        std::error_code ec;
        fs::remove(tmp, ec);
        return internal("write " + path + ": " + err);
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) return internal("rename " + tmp.string() + " -> " + path + ": " + ec.message());
    return {};
}

Result<HostImage> readImage(const std::string& path) {
    auto in = ImageInput::open(path);
    if (!in) return badInput(path + ": cannot read image (" + OIIO::geterror() + ")");
    const ImageSpec& spec = in->spec();
    HostImage img(spec.width, spec.height, spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, img.pixels.data()))
        return badInput(path + ": corrupt image (" + in->geterror() + ")");
    in->close();
    return img;
}

}  // namespace cavity
