#include "measure/runner.h"

#include "pipeline/config_id.h"
#include "images/gbuffer_import.h"
#include "images/image_io.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <unistd.h>

namespace cavity::measure {

namespace fs = std::filesystem;

Status checkWritableDir(const std::string& flag, const std::string& dir, size_t longestInside) {
    if (dir.empty()) return badInput(flag + " '': empty value (name an output folder)");
    std::error_code ec;
    const fs::path p = fs::absolute(dir, ec);
    if (ec) return badInput(flag + " " + dir + ": not a usable path (" + ec.message() + ")");
    if (fs::exists(p, ec) && !fs::is_directory(p, ec))
        return badInput(flag + " " + dir + ": exists and is not a folder");
    fs::path existing = p;
    while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.parent_path();
    if (existing.empty() || !fs::is_directory(existing, ec))
        return badInput(flag + " " + dir + ": cannot be created (" + existing.string() + " is not a folder)");
    // Every file goes to dir/<configuration id>/<image>: the whole path and
    // each name in it must fit the file system's limits before anything renders.
    const long nameMax = ::pathconf(existing.c_str(), _PC_NAME_MAX), pathMax = ::pathconf(existing.c_str(), _PC_PATH_MAX);
    for (const auto& part : p)
        if (nameMax > 0 && long(part.string().size()) > nameMax)
            return badInput(flag + " " + dir.substr(0, 60) + "...: too long: a folder name of " +
                            std::to_string(part.string().size()) + " characters (at most " + std::to_string(nameMax) + ")");
    if (pathMax > 0 && long(p.string().size() + longestInside) >= pathMax)
        return badInput(flag + " " + dir.substr(0, 60) + "...: too long: " + std::to_string(p.string().size()) +
                        " characters, and the files inside need " + std::to_string(longestInside) + " more (at most " +
                        std::to_string(pathMax - 1) + " in all)");
    // Permission bits do not tell (root passes access(); /proc refuses
    // mkdir), so make and remove a probe folder where dir would be created.
    std::string probe = (existing / ".cavity-probe-XXXXXX").string();
    if (::mkdtemp(probe.data()) == nullptr)
        return badInput(flag + " " + dir + ": cannot be written (making a folder in " + existing.string() + " failed: " + std::strerror(errno) + ")");
    ::rmdir(probe.c_str());
    return {};
}

Status checkOutputFiles(const std::string& flag, const std::string& dir, const std::vector<std::string>& names) {
    for (const auto& name : names) {
        std::error_code ec;
        const fs::path p = fs::path(dir) / name;
        if (fs::exists(p, ec) && !fs::is_regular_file(p, ec))
            return badInput(flag + " " + dir + ": " + p.string() + " is " +
                            (fs::is_directory(p, ec) ? "a folder" : "not a regular file") + " (the " + name +
                            " written there at the end; move it away or give another " + flag + ")");
    }
    return {};
}

Status checkWritableFile(const std::string& flag, const std::string& file) {
    if (file.empty()) return badInput(flag + " '': empty value (name an output file)");
    std::error_code ec;
    const fs::path p = fs::absolute(file, ec);
    if (ec) return badInput(flag + " " + file + ": not a usable path (" + ec.message() + ")");
    if (fs::is_directory(p, ec)) return badInput(flag + " " + file + ": is a folder (a file is expected)");
    if (fs::exists(p, ec) && !fs::is_regular_file(p, ec)) return badInput(flag + " " + file + ": exists and is not a file");
    const fs::path parent = p.parent_path();
    if (!fs::is_directory(parent, ec)) return badInput(flag + " " + file + ": folder " + parent.string() + " does not exist");
    std::string probe = (parent / ".cavity-probe-XXXXXX").string();
    if (::mkdtemp(probe.data()) == nullptr)
        return badInput(flag + " " + file + ": cannot be written (making a folder in " + parent.string() + " failed: " + std::strerror(errno) + ")");
    ::rmdir(probe.c_str());
    return {};
}

TimingOptions timingOptions(const gpu::DeviceInfo& device, const RunOptions& o) {
    TimingOptions t = defaultTimingOptions(device);
    t.warmup = o.warmup;
    t.frames = o.frames;
    if (o.mode) t.mode = *o.mode;
    if (o.maxNoise) t.maxNoise = *o.maxNoise;
    if (o.maxSeconds) {
        t.maxSeconds = *o.maxSeconds;
        t.hardTimeLimit = true;   // the user's limit bounds the run, --frames or not
    }
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
        r.passShapes.push_back(chain->passShape(i));
    }
    r.pipelines = chain->pipelineInfos();
    r.timingOptions = timingOptions(gpu.info(), o);
    GpuClocks* clocks = GpuClocks::forDevice(gpu.info());
    r.floorDevice = deviceFloor(gpu.info(), clocks ? clocks->maxSmMhz() : std::nullopt);
    // More views: more chains measured in turn (an imported G-buffer has one).
    std::vector<std::unique_ptr<PassChain>> others;
    std::vector<PassChain*> turn{chain.get()};
    for (int view = 1; view < (c.imported() ? 1 : o.views); ++view) {
        RunConfig v = c;
        v.params["view"] = view;
        CAVITY_ASSIGN(auto other, PassChain::create(gpu, v, o.overrides));
        others.push_back(std::move(other));
        turn.push_back(others.back().get());
    }
    r.views = int(turn.size());
    CAVITY_ASSIGN(r.timing, measurePasses(gpu, turn, r.timingOptions, clocks));
    r.debugMessages = gpu.takeDebugMessages();
    CAVITY_ASSIGN(r.nonFinite, chain->findNonFinite());
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

}  // namespace cavity::measure