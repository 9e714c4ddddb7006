// gate merge's images, and a gate's output moved in at its end (gate_outputs.h).
#include "gate_outputs.h"
#include "report/gate_report.h"
#include "staging.h"

#include <system_error>

namespace cavity::cli {

namespace fs = std::filesystem;

namespace {

// A configuration id as a path under images/: relative, no "." or "..",
// so that a damaged gate.json cannot name a folder outside either tree.
bool safeId(const std::string& id) {
    const fs::path p(id);
    if (id.empty() || p.is_absolute()) return false;
    for (const auto& part : p)
        if (part.empty() || part == "." || part == "..") return false;
    return true;
}

// Hard links where the shard and the merge share a file system (the
// images are never written again), a copy where they do not.
Status copyTree(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::create_hard_links, ec);
    if (!ec) return {};
    fs::remove_all(to, ec);
    fs::copy(from, to, fs::copy_options::recursive, ec);
    if (ec) return badInput("--out: cannot copy " + from.string() + " to " + to.string() + ": " + ec.message());
    return {};
}

}  // namespace

Status gatherShardImages(const std::map<std::string, std::string>& owner, const std::string& out, gate::GateRun& merged) {
    std::error_code ec;
    fs::create_directories(out, ec);
    const fs::path staging = stagingDir(out);
    fs::create_directories(staging, ec);
    if (ec) return badInput("--out " + out + ": cannot create " + staging.string() + ": " + ec.message());
    for (const auto& [id, shard] : owner) {
        if (!safeId(id)) {
            fs::remove_all(staging, ec);
            return badInput(shard + "/gate.json: configuration id '" + id + "' is not a relative path of names");
        }
        const fs::path from = fs::path(shard) / "images" / id;
        if (!fs::is_directory(from, ec)) continue;   // an error before any image was written
        if (auto st = copyTree(from, staging / id); !st) {
            fs::remove_all(staging, ec);
            return st;
        }
    }
    // A previous merge's images are replaced whole (staging.h).
    if (ec = replaceFolder(staging, fs::path(out) / "images"); ec)
        return badInput("--out " + out + ": cannot move the images in: " + ec.message());
    for (auto& r : merged.results)
        for (auto& i : r.images)
            for (std::string* p : {&i.newExact, &i.newPng, &i.diffPng}) *p = inFolder(out, *p);
    return {};
}

Status writeGateOutput(gate::GateRun& run, const fs::path& staging, const std::string& out, const std::string& reportUrl) {
    std::error_code ec;
    gate::dropStaleReports(out);
    const fs::path images = fs::path(out) / "images";
    if (fs::is_directory(staging / "images", ec))
        ec = replaceFolder(staging / "images", images);
    else
        fs::remove_all(images, ec);
    std::error_code gone;
    fs::remove_all(staging, gone);
    if (ec) return badInput("--out " + out + ": cannot move the images in: " + ec.message());
    for (auto& r : run.results)
        for (auto& i : r.images)
            for (std::string* p : {&i.newExact, &i.newPng, &i.diffPng}) *p = inFolder(out, *p);
    return report::writeReports(run, out, reportUrl);
}

}  // namespace cavity::cli
