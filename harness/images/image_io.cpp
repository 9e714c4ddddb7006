#include "images/image_module.h"
#include "images/oiio_pixels.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace cavity::images::oiio {

namespace fs = std::filesystem;
using namespace OIIO;

Status writeImage(const std::string& path, const HostImage& img, Encoding enc, bool sixteenBit) {
    const std::string ext = fs::path(path).extension().string();
    const bool exr = ext == ".exr";
    if (!exr && ext != ".png") return badInput(path + ": unsupported image extension (use .exr or .png)");
    int channels = img.channels;
    if (!exr && channels == 2) channels = 3;
    // A normal's fourth channel is no alpha: as PNG alpha (0.5 where it is
    // 0) it made the picture half transparent, its colours divided by it.
    if (!exr && enc == Encoding::SignedUnit && channels == 4) channels = 3;
    ImageSpec spec(img.width, img.height, channels, exr ? TypeDesc::HALF : (sixteenBit ? TypeDesc::UINT16 : TypeDesc::UINT8));
    if (exr) spec.attribute("compression", "zip");
    if (enc == Encoding::Preview) spec.attribute("png:compressionLevel", 1);
    std::vector<float> px(size_t(img.width) * img.height * channels, 0.0f);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
        for (int c = 0; c < std::min(img.channels, channels); ++c) {
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

namespace {

// libpng prints "libpng error: ..." on stderr itself before OpenImageIO
// reports the same failure, in several lines. While a file is read, stderr
// goes to a temporary file; what was printed joins our one-line message.
class StderrCapture {
public:
    StderrCapture() {
        std::fflush(stderr);
        file_ = std::tmpfile();
        saved_ = file_ ? ::dup(2) : -1;
        if (saved_ >= 0) ::dup2(::fileno(file_), 2);
    }
    ~StderrCapture() { release(); }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;
    // Restores stderr and returns what was printed meanwhile.
    std::string release() {
        std::string text;
        if (saved_ < 0) return text;
        std::fflush(stderr);
        ::dup2(saved_, 2);
        ::close(saved_);
        saved_ = -1;
        std::rewind(file_);
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) text.append(buf, n);
        std::fclose(file_);
        file_ = nullptr;
        return text;
    }

private:
    std::FILE* file_ = nullptr;
    int saved_ = -1;
};

// The distinct lines of several messages, joined with "; ".
std::string oneLine(const std::vector<std::string>& messages) {
    std::vector<std::string> lines;
    for (const auto& m : messages) {
        size_t start = 0;
        while (start <= m.size()) {
            size_t end = m.find('\n', start);
            if (end == std::string::npos) end = m.size();
            std::string line = m.substr(start, end - start);
            while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
            if (!line.empty() && std::find(lines.begin(), lines.end(), line) == lines.end()) lines.push_back(line);
            start = end + 1;
        }
    }
    std::string out;
    for (const auto& l : lines) out += (out.empty() ? "" : "; ") + l;
    return out.empty() ? "no reason given" : out;
}

}  // namespace

// Asked for floats, OpenImageIO 2.4's read_scanlines converts through a
// scratch buffer of about 64 MiB whatever the image's size: free in a
// release build (pages never touched), but under ASan every such buffer has
// its 8 MiB of shadow written when allocated and again when freed, which made
// a small read many times slower than a read in the file's own type
// (TypeDesc::UNKNOWN, the one type 2.4 reads straight into the caller's
// buffer), and a large part of a gate run on the sanitizer build. So the file's own
// type is read, and converted with the function read_scanlines converts
// with (the same floats, checked on every stored baseline).
bool readFloats(ImageInput& in, HostImage& img) {
    const ImageSpec& spec = in.spec();
    if (!spec.channelformats.empty())   // a type per channel
        return in.read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, img.pixels.data());
    if (spec.format == TypeDesc::FLOAT)
        return in.read_image(0, 0, 0, spec.nchannels, TypeDesc::UNKNOWN, img.pixels.data());
    std::vector<unsigned char> native(spec.image_bytes(true));
    if (!in.read_image(0, 0, 0, spec.nchannels, TypeDesc::UNKNOWN, native.data())) return false;
    return convert_pixel_values(spec.format, native.data(), TypeDesc::FLOAT, img.pixels.data(), int(img.pixels.size()));
}

Result<HostImage> readImage(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return badInput(path + ": is a folder, not an image");
    StderrCapture capture;
    auto in = ImageInput::open(path);
    if (!in) {
        const std::string err = OIIO::geterror();
        return badInput(path + ": cannot read image (" + oneLine({capture.release(), err}) + ")");
    }
    const ImageSpec& spec = in->spec();
    HostImage img(spec.width, spec.height, spec.nchannels);
    if (!readFloats(*in, img)) {
        const std::string err = in->geterror();
        return badInput(path + ": corrupt image (" + oneLine({capture.release(), err}) + ")");
    }
    in->close();
    return img;
}

}  // namespace cavity::images::oiio
