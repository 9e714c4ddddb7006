#include "core/camera.h"
#include "images/gbuffer_import.h"
#include "images/image_module.h"
#include "images/oiio_pixels.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

namespace cavity::images::oiio {

namespace fs = std::filesystem;
using namespace OIIO;

namespace {

std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

std::string pixelName(size_t i, int width) {
    return "pixel (" + std::to_string(i % size_t(width)) + ", " + std::to_string(i / size_t(width)) + ")";
}

// An OpenImageIO message on one line (the error contract: one line).
std::string oneLine(std::string m) {
    std::replace(m.begin(), m.end(), '\n', ' ');
    while (!m.empty() && m.back() == ' ') m.pop_back();
    return m;
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
}

// The file's channels, read one at a time (as float) by name.
class Capture {
public:
    Capture(std::string path, std::unique_ptr<ImageInput> in) : path_(std::move(path)), in_(std::move(in)) {}
    const ImageSpec& spec() const { return in_->spec(); }
    bool has(const std::string& name) const { return index(name) >= 0; }
    std::string channelList() const { return spec().channelnames.empty() ? "none" : join(spec().channelnames); }

    Error error(const std::string& what) const { return badInput("--gbuffer-file " + path_ + ": " + what); }

    // All three of a group or (when optional) none; the message names the
    // first one missing and lists what the file has.
    Result<bool> group(const std::vector<std::string>& names, bool optional) const {
        std::vector<std::string> missing;
        for (const auto& n : names)
            if (!has(n)) missing.push_back(n);
        if (missing.empty()) return true;
        if (optional && missing.size() == names.size()) return false;
        return error("no channel " + missing[0] + ": need " + join(names) + (optional ? " (or none of them)" : "") +
                     " (the file has: " + channelList() + ")");
    }

    // A channel's values, rows top to bottom; the first non-finite value is
    // an error naming the channel and the pixel.
    Result<std::vector<float>> read(const std::string& name) {
        const int c = index(name);
        const ImageSpec& s = spec();
        // Every channel at the first read, in one call: a read of one
        // channel as floats costs what a whole image does (oiio_pixels.h).
        if (pixels_.pixels.empty()) {
            pixels_ = HostImage(s.width, s.height, s.nchannels);
            if (!readFloats(*in_, pixels_)) {
                pixels_ = HostImage{};
                return error("channel " + name + " cannot be read (" + oneLine(in_->geterror()) + ")");
            }
        }
        std::vector<float> v(size_t(s.width) * size_t(s.height));
        for (size_t i = 0; i < v.size(); ++i) v[i] = pixels_.pixels[i * size_t(s.nchannels) + size_t(c)];
        for (size_t i = 0; i < v.size(); ++i)
            if (!std::isfinite(v[i]))
                return error("channel " + name + " is " + fmt(v[i]) + " at " + pixelName(i, s.width) + ": must be finite");
        return v;
    }

private:
    int index(const std::string& name) const {
        const auto& n = spec().channelnames;
        const auto it = std::find(n.begin(), n.end(), name);
        return it == n.end() ? -1 : int(it - n.begin());
    }
    std::string path_;
    std::unique_ptr<ImageInput> in_;
    HostImage pixels_;   // every channel, once read
};

Result<Capture> open(const std::string& path) {
    const std::string head = "--gbuffer-file " + path + ": ";
    std::error_code ec;
    if (!fs::exists(path, ec)) return badInput(head + "no such file");
    if (fs::is_directory(path, ec)) return badInput(head + "is a directory: must be a multi-channel OpenEXR file");
    auto in = ImageInput::open(path);
    if (!in) {
        return badInput(head + "cannot be read as an image (" + oneLine(OIIO::geterror()) +
                        "): must be a multi-channel OpenEXR file");
    }
    const std::string format = in->format_name();
    if (format != "openexr")
        return badInput(head + "is a " + format + " file: must be a multi-channel OpenEXR file");
    const ImageSpec& s = in->spec();
    if (s.deep) return badInput(head + "holds deep data: must be a flat (scanline or tiled) OpenEXR image");
    if (s.x != 0 || s.y != 0 || s.width != s.full_width || s.height != s.full_height || s.full_x != 0 || s.full_y != 0)
        return badInput(head + "data window " + std::to_string(s.width) + "x" + std::to_string(s.height) + " at (" +
                        std::to_string(s.x) + ", " + std::to_string(s.y) + ") differs from the display window " +
                        std::to_string(s.full_width) + "x" + std::to_string(s.full_height) + " at (" +
                        std::to_string(s.full_x) + ", " + std::to_string(s.full_y) + "): they must be the same");
    // An OpenEXR file holds an offset table of 8 bytes a chunk after its
    // header and at least 8 more a chunk (its position and size): a header
    // whose size needs more than the file has is cut short or edited, and is
    // refused before the pixels are allocated (a 400-byte file claiming
    // 16384x16384 once took 4 GB, then failed).
    const std::string compression = s.get_string_attribute("compression", "zip");
    const int lines = compression == "none" || compression == "rle" || compression == "zips" ? 1
                      : compression == "zip" || compression == "pxr24"                      ? 16
                      : compression == "dwab"                                               ? 256
                                                                                            : 32;
    const uint64_t chunks = s.tile_width > 0 ? uint64_t((s.width + s.tile_width - 1) / s.tile_width) *
                                                   uint64_t((s.height + s.tile_height - 1) / std::max(1, s.tile_height))
                                             : uint64_t((s.height + lines - 1) / lines);
    const auto bytes = fs::file_size(path, ec);
    if (!ec && bytes < 16 * chunks)
        return badInput(head + "cut short: its header says " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                        ", which needs at least " + std::to_string(16 * chunks) + " bytes, and the file has " +
                        std::to_string(bytes));
    return Capture(path, std::move(in));
}

// The channels the import uses, by name; which groups the file has.
struct Channels {
    std::map<std::string, std::vector<float>> planes;
    bool hasP = false;
    bool hasAlbedo = false;
};

// Which channels: all missing ones are reported before any is read.
Result<Channels> readChannels(Capture& cap) {
    CAVITY_ASSIGN(const bool hasP, cap.group({"P.X", "P.Y", "P.Z"}, true));
    if (!hasP && !cap.has("Z"))
        return cap.error("no position: need channels P.X, P.Y, P.Z or a channel Z (the file has: " + cap.channelList() + ")");
    CAVITY_ASSIGN(const bool hasN, cap.group({"N.X", "N.Y", "N.Z"}, false));
    (void)hasN;
    CAVITY_ASSIGN(const bool hasAlbedo, cap.group({"albedo.R", "albedo.G", "albedo.B"}, true));
    Channels c;
    c.hasP = hasP;
    c.hasAlbedo = hasAlbedo;
    auto& ch = c.planes;
    for (const char* n : {"P.X", "P.Y", "P.Z"})
        if (hasP) { CAVITY_ASSIGN(ch[n], cap.read(n)); }
    if (!hasP) { CAVITY_ASSIGN(ch["Z"], cap.read("Z")); }
    for (const char* n : {"N.X", "N.Y", "N.Z"}) { CAVITY_ASSIGN(ch[n], cap.read(n)); }
    if (hasAlbedo)
        for (const char* n : {"albedo.R", "albedo.G", "albedo.B"}) { CAVITY_ASSIGN(ch[n], cap.read(n)); }
    return c;
}

}  // namespace

Result<GBufferImages> importGBuffer(const std::string& path, int width, int height, FrameFn frameOf) {
    CAVITY_ASSIGN(Capture cap, open(path));
    const int w = cap.spec().width, h = cap.spec().height;
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    if (w < 1 || h < 1 || w > kMaxResolution || h > kMaxResolution)
        return cap.error("size " + size + ": must be WIDTHxHEIGHT with each in 1.." + std::to_string(kMaxResolution));
    if ((width || height) && (w != width || h != height))
        return cap.error("wrong size " + size + ": must be the run's --res " + std::to_string(width) + "x" +
                         std::to_string(height) + " (leave out --res to take the file's size)");

    CAVITY_ASSIGN(Channels channels, readChannels(cap));
    const bool hasP = channels.hasP, hasAlbedo = channels.hasAlbedo;
    auto& ch = channels.planes;

    GBufferImages g;
    g.position = HostImage(w, h, 4);
    g.normal = HostImage(w, h, 4);
    g.albedo = HostImage(w, h, 4);
    // The same arithmetic as viewRayAt (kernels/include/common.glsl), in float.
    const auto frame = frameOf(w, h, w, h);
    char rangeText[64];
    std::snprintf(rangeText, sizeof rangeText, "[%g, %g]", double(kNear), double(kFar));
    const std::string depthRange = rangeText;
    auto plane = [&](const char* name) { return ch.count(name) ? ch[name].data() : nullptr; };
    const float *px = plane("P.X"), *py = plane("P.Y"), *pz = plane("P.Z"), *zd = plane("Z");
    const float *nx = plane("N.X"), *ny = plane("N.Y"), *nz = plane("N.Z");
    const float* albedo[3] = {plane("albedo.R"), plane("albedo.G"), plane("albedo.B")};
    size_t surfaces = 0;
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
        const int x = int(i % size_t(w)), y = int(i / size_t(w));
        float p[3];
        float depth;
        if (hasP) {
            p[0] = px[i];
            p[1] = py[i];
            p[2] = pz[i];
            depth = -p[2];
            if (depth <= 0) continue;   // background: P.Z >= 0
            if (depth < kNear || depth > kFar)
                return cap.error("channel P.Z is " + fmt(p[2]) + " at " + pixelName(i, w) + ": a surface's depth -P.Z must be in " +
                                 depthRange + " (the harness projection's near and far; P.Z >= 0 marks background)");
        } else {
            depth = zd[i];
            if (depth <= 0) continue;   // background
            if (depth < kNear || depth > kFar)
                return cap.error("channel Z is " + fmt(depth) + " at " + pixelName(i, w) + ": a surface's depth must be in " +
                                 depthRange + " (the harness projection's near and far; Z <= 0 marks background)");
            const float ndcX = (float(x) + 0.5f) * frame.invSize[0] * 2.0f - 1.0f;
            const float ndcY = (float(y) + 0.5f) * frame.invSize[1] * 2.0f - 1.0f;
            const float ray[3] = {ndcX * frame.camera[0], -ndcY * frame.camera[1], -1.0f};
            for (int k = 0; k < 3; ++k) p[k] = ray[k] * depth;
        }
        float n[3] = {nx[i], ny[i], nz[i]};
        const double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        if (!(len > 1e-12))
            return cap.error("channels N.X, N.Y, N.Z are (" + fmt(n[0]) + ", " + fmt(n[1]) + ", " + fmt(n[2]) + ") at " +
                             pixelName(i, w) + ", a surface pixel: the normal must be nonzero");
        // Half-float storage leaves a unit normal within 2^-11 of unit
        // length; such a normal is used as it is, so that a capture of a
        // harness G-buffer comes back bit for bit. Others are renormalised.
        if (std::fabs(len - 1.0) > 1e-3)
            for (float& v : n) v = float(double(v) / len);
        for (int k = 0; k < 3; ++k) {
            g.position.at(x, y, k) = p[k];
            g.normal.at(x, y, k) = n[k];
            g.albedo.at(x, y, k) = hasAlbedo ? std::clamp(albedo[k][i], 0.0f, 1.0f) : kImportDefaultAlbedo;
        }
        g.position.at(x, y, 3) = depth;
        g.albedo.at(x, y, 3) = 1.0f;
        ++surfaces;
    }
    // A frame of background alone has nothing to occlude: its AO would be
    // timed and judged as a result.
    if (surfaces == 0)
        return cap.error("every pixel is background (" + std::string(hasP ? "P.Z >= 0" : "Z <= 0") +
                         " everywhere): a capture needs surfaces to measure");
    return g;
}

}  // namespace cavity::images::oiio
