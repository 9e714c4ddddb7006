#include "runner.h"

#include "gbuffer_import.h"
#include "image_io.h"

#include <filesystem>

#include <unistd.h>

namespace cavity {

namespace fs = std::filesystem;

Status checkWritableDir(const std::string& flag, const std::string& dir) {
    std::error_code ec;
    fs::path p = fs::absolute(dir, ec);
    if (fs::exists(p, ec) && !fs::is_directory(p, ec))
        return badInput(flag + " " + dir + ": exists and is not a directory");
    while (!p.empty() && !fs::exists(p, ec)) p = p.parent_path();
    if (p.empty() || !fs::is_directory(p, ec) || ::access(p.c_str(), W_OK | X_OK) != 0)
        return badInput(flag + " " + dir + ": cannot be written (" + p.string() + " is not writable)");
    return {};
}

TimingOptions timingOptions(const gpu::DeviceInfo& device, const RunOptions& o) {
    TimingOptions t = defaultTimingOptions(device);
    t.warmup = o.warmup;
    t.frames = o.frames;
    if (o.mode) t.mode = *o.mode;
    if (o.maxNoise) t.maxNoise = *o.maxNoise;
    if (o.maxSeconds) t.maxSeconds = *o.maxSeconds;
    return t;
}

Result<RunRecord> runConfig(gpu::Backend& gpu, const RunConfig& given, const RunOptions& o) {
    RunConfig c = given;
    if (c.imported() && !c.gbufferImages) {
        CAVITY_ASSIGN(auto images, importGBuffer(c.gbufferFile, c.width, c.height));
        c.gbufferImages = std::make_shared<const GBufferImages>(std::move(images));
    }
    CAVITY_ASSIGN(auto chain, PassChain::create(gpu, c, o.overrides));
    RunRecord r;
    r.config = c;
    r.device = gpu.info();
    r.passes = chain->passes();
    for (size_t i = 0; i < chain->passCount(); ++i) {
        const bool half = r.passes[i].half;
        r.passSizes.push_back({half ? (c.width + 1) / 2 : c.width, half ? (c.height + 1) / 2 : c.height});
    }
    r.shaderPaths = chain->shaderPaths();
    r.timingOptions = timingOptions(gpu.info(), o);
    CAVITY_ASSIGN(r.timing, measure(gpu, *chain, r.timingOptions, GpuClocks::forDevice(gpu.info())));
    r.debugMessages = gpu.takeDebugMessages();
    if (o.keepImages || o.checkDeterminism) {
        for (const auto& out : userOutputs(c)) {
            CAVITY_ASSIGN(HostImage img, chain->read(out.image));
            r.pixels[out.image] = std::move(img);
        }
    }
    if (o.checkDeterminism) {
        // Per-pixel noise is seeded by pixel position only, so another frame
        // must give the same bits.
        gpu.beginFrame();
        chain->record();
        CAVITY_TRY(gpu.endFrame());
        for (const auto& out : userOutputs(c)) {
            CAVITY_ASSIGN(HostImage again, chain->read(out.image));
            if (again.pixels != r.pixels[out.image].pixels) r.deterministic = false;
        }
    }
    if (!o.outDir.empty()) {
        const std::string id = configId(c);
        const fs::path dir = fs::path(o.outDir) / id;
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) return badInput("--out " + o.outDir + ": cannot create " + dir.string() + ": " + ec.message());
        for (const auto& out : userOutputs(c)) {
            CAVITY_ASSIGN(HostImage img, chain->read(out.image));
            const Encoding enc = out.image == "normal" ? Encoding::SignedUnit : Encoding::Linear;
            const std::string base = (dir / out.image).string();
            CAVITY_TRY(writeImage(base + ".exr", img));
            CAVITY_TRY(writeImage(base + ".png", img, enc));
            r.images[out.image] = {{"exr", id + "/" + out.image + ".exr"}, {"png", id + "/" + out.image + ".png"}};
        }
    }
    return r;
}

}  // namespace cavity
