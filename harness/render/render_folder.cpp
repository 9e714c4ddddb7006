#include "render/render_folder.h"

#include "measure/results.h"

#include <filesystem>

namespace cavity::render {

namespace fs = std::filesystem;

FolderWriter::FolderWriter(std::string dir, RenderManifest manifest, plan::Approvals approved)
    : dir_(std::move(dir)), manifest_(std::move(manifest)), approved_(std::move(approved)) {}

Status FolderWriter::begin() {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) return badInput("--out " + dir_ + ": cannot create: " + ec.message());
    fs::remove(fs::path(dir_) / "manifest.json", ec);
    if (ec) return badInput("--out " + dir_ + ": cannot remove the old manifest.json: " + ec.message());
    return {};
}

Status FolderWriter::add(Rendering&& r) {
    auto [it, fresh] = byIndex_.try_emplace(r.index, manifest_.configs.size());
    if (fresh) manifest_.configs.push_back({r.index, r.id, r.key, gpu::apiName(r.config.api), r.device.deviceName, {}});
    ConfigEntry& c = manifest_.configs[it->second];
    if (c.device.empty()) c.device = r.device.deviceName;
    if (!r.device.deviceName.empty()) manifest_.devices[gpu::apiName(r.config.api)] = r.device;

    RenderEntry e{r.repetition, r.error, r.errorCode, r.deterministic, r.timings, {}};
    const RenderEntry* first = c.renders.empty() ? nullptr : &c.renders.front();
    const fs::path dir = fs::path("images") / r.id;
    for (const auto& ci : plan::checkedImages()) {
        auto img = r.images.find(ci.name);
        if (img == r.images.end()) continue;   // the configuration did not run
        ImageEntry i;
        i.name = ci.name;
        i.stored = {img->second.width, img->second.height, img->second.channels, r.digests.at(ci.name), 0};
        bool same = false;
        if (first)
            for (const auto& f : first->images) same |= f.name == ci.name && f.stored.digest == i.stored.digest;
        // An approved digest (positive for this class, or known bad) needs no
        // pixels to be judged: only its digest travels.
        same |= approved_.find(r.key, ci.name, i.stored.digest, plan::deviceClass(r.device.deviceName)) != nullptr;
        // Judged here and passed: its verdict and metrics travel instead.
        if (const auto k = r.judged.find(ci.name); k != r.judged.end()) {
            i.judged = k->second;
            same |= k->second.passed;
        }
        const std::string content = r.key + "|" + ci.name + "|" + i.stored.digest;
        if (auto known = stored_.find(content); !same && known != stored_.end()) {
            i.file = known->second.first;
            i.stored.bytes = known->second.second;
        } else if (!same) {
            const std::string suffix = r.repetition ? ".rep" + std::to_string(r.repetition) : "";
            i.file = (dir / (ci.name + suffix + ".f32z")).string();
            std::error_code ec;
            fs::create_directories(fs::path(dir_) / dir, ec);
            if (ec) return badInput("--out " + dir_ + ": cannot create " + (fs::path(dir_) / dir).string() + ": " + ec.message());
            CAVITY_ASSIGN(i.stored.bytes, writeImageFile((fs::path(dir_) / i.file).string(), img->second));
            bytes_ += i.stored.bytes;
            ++files_;
            stored_[content] = {i.file, i.stored.bytes};
        }
        e.images.push_back(std::move(i));
    }
    c.renders.push_back(std::move(e));
    return {};
}

Status FolderWriter::finish(const std::vector<BackendFailure>& failures, double seconds) {
    // A backend that fails to start fails every repetition: list it once.
    for (const auto& f : failures) {
        bool seen = false;
        for (const auto& e : manifest_.backendErrors) seen |= e.api == gpu::apiName(f.api) && e.message == f.message;
        if (!seen) manifest_.backendErrors.push_back({gpu::apiName(f.api), int(ErrorCode::BackendUnavailable), f.message});
    }
    manifest_.seconds = seconds;
    return writeJson((fs::path(dir_) / "manifest.json").string(), toJson(manifest_));
}

}  // namespace cavity::render
