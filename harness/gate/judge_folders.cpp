#include "gate/judge_folders.h"

#include "plan/approvals.h"

#include "pipeline/config_id.h"
#include "gate/gate_judge.h"
#include "render/image_file.h"
#include "core/json_input.h"
#include "render/render_manifest.h"
#include "measure/results.h"
#include "core/progress.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

namespace cavity::gate {

namespace fs = std::filesystem;

namespace {

struct Folder {
    std::string dir, path;   // the folder, its manifest.json
    render::RenderManifest m;
};

Result<Folder> readFolder(const std::string& dir) {
    Folder f;
    f.dir = dir;
    f.path = (fs::path(dir) / "manifest.json").string();
    if (!fs::exists(f.path))
        return badInput(f.path + ": missing (not a render folder, or its cavity_render did not finish)");
    CAVITY_ASSIGN(auto j, readJsonFile(f.path));
    CAVITY_ASSIGN(f.m, render::parseManifest(j, f.path));
    return f;
}

std::string label(const render::ConfigEntry& c, const render::RenderEntry& r) {
    return c.id + (r.repetition ? " (repetition " + std::to_string(r.repetition) + ")" : "");
}

// A file named by a manifest must lie inside its folder.
bool inside(const std::string& file) {
    const fs::path p(file);
    if (p.empty() || p.is_absolute()) return false;
    for (const auto& part : p)
        if (part == "..") return false;
    return true;
}

// Everything but the pixels: the entries belong to the matrix and the
// folder's shard, no entry is in two folders, every repetition is there,
// each image has the configuration's shape, and an image without a file
// is one whose digest repetition 0 has.
bool sameAsFirst(const render::ConfigEntry& c, const std::string& image, const std::string& digest) {
    for (const auto& first : c.renders[0].images)
        if (first.name == image && first.stored.digest == digest) return true;
    return false;
}

Status checkEntries(const Folder& f, const std::vector<RunConfig>& all, std::map<std::string, std::string>& owner,
                    const plan::Approvals& approved) {
    const auto& m = f.m;
    const std::string shard = std::to_string(m.shardIndex) + "/" + std::to_string(m.shardCount);
    for (const auto& c : m.configs) {
        if (c.index >= all.size() || configId(all[c.index]) != c.id)
            return badInput(f.path + ": " + c.id + " is not entry " + std::to_string(c.index) + " of matrix " + m.matrix +
                            (c.index < all.size() ? " (that is " + configId(all[c.index]) + ")" : ""));
        const RunConfig& cfg = all[c.index];
        if (c.key != baselineKey(cfg) || c.api != gpu::apiName(cfg.api))
            return badInput(f.path + ": " + c.id + ": baseline_key " + c.key + " and api " + c.api + " (the id gives " +
                            baselineKey(cfg) + " and " + gpu::apiName(cfg.api) + ")");
        if (!inShard(c.index, m.shardIndex, m.shardCount))
            return badInput(f.path + ": " + c.id + " (entry " + std::to_string(c.index) + ") is not in shard " + shard);
        if (auto [it, fresh] = owner.emplace(c.id, f.path); !fresh)
            return badInput(f.path + ": " + c.id + " is also in " + it->second + " (the folders' shards overlap)");
        if (c.renders.size() != size_t(m.repeat))
            return badInput(f.path + ": " + c.id + " has " + std::to_string(c.renders.size()) + " renders, repeat is " +
                            std::to_string(m.repeat));
        for (size_t k = 0; k < c.renders.size(); ++k) {
            const auto& r = c.renders[k];
            if (r.repetition != int(k))
                return badInput(f.path + ": " + c.id + ": render " + std::to_string(k) + " says repetition " +
                                std::to_string(r.repetition));
            if (!r.error.empty()) continue;
            if (r.images.size() != checkedImages().size())
                return badInput(f.path + ": " + label(c, r) + " has " + std::to_string(r.images.size()) + " images (needs " +
                                std::to_string(checkedImages().size()) + ": ao, ao_blur, color)");
            for (const auto& ci : checkedImages()) {
                const auto i = std::find_if(r.images.begin(), r.images.end(), [&](const auto& e) { return e.name == ci.name; });
                if (i == r.images.end()) return badInput(f.path + ": " + label(c, r) + " lacks image " + ci.name);
                const ImageShape need = checkedShape(cfg, ci.name), have{i->stored.width, i->stored.height, i->stored.channels};
                if (!(have == need))
                    return badInput(f.path + ": " + label(c, r) + ": " + ci.name + " is " + shapeText(have) +
                                    ", the configuration renders " + shapeText(need));
                if (!i->file.empty() && !inside(i->file))
                    return badInput(f.path + ": " + label(c, r) + ": " + ci.name + " file " + i->file + " is outside the folder");
                if (i->file.empty() && !(k > 0 && sameAsFirst(c, ci.name, i->stored.digest)) &&
                    !approved.find(c.key, ci.name, i->stored.digest, plan::deviceClass(c.device)) &&
                    !(i->judged && i->judged->passed))
                    return badInput(f.path + ": " + label(c, r) + ": " + ci.name +
                                    " has no file, is not repetition 0's image, its digest is not approved, and it "
                                    "was not judged to pass where it was rendered");
            }
        }
    }
    return {};
}

// A folder holds every configuration its manifest's filter and shard select
// on each API that started: one left out (a damaged or hand-edited manifest)
// would otherwise never be judged, and the verdict would still read "all
// passed".
Status checkComplete(const Folder& f, const Matrix& matrix) {
    const auto& m = f.m;
    CAVITY_ASSIGN(const auto selected, plan::selectEntries(matrix, m.shardIndex, m.shardCount, m.filter));
    std::set<size_t> have;
    for (const auto& c : m.configs) have.insert(c.index);
    for (const auto& e : selected)
        if (m.devices.count(gpu::apiName(e.config.api)) && !have.count(e.index))
            return badInput(f.path + ": " + configId(e.config) + " (entry " + std::to_string(e.index) + ") is missing: shard " +
                            std::to_string(m.shardIndex) + "/" + std::to_string(m.shardCount) +
                            (m.filter.empty() ? "" : " of filter " + m.filter) + " selects it, and " +
                            gpu::apiName(e.config.api) + " started");
    return {};
}

// Every stored image inflates to the recorded shape and digest. The pixels
// are dropped again: a 1920x1080 matrix does not fit in memory at once.
Status checkFiles(const Folder& f) {
    for (const auto& c : f.m.configs)
        for (const auto& r : c.renders)
            for (const auto& i : r.images) {
                if (i.file.empty()) continue;
                auto image = render::readImageFile((fs::path(f.dir) / i.file).string(), i.stored);
                if (!image) return image.error();
            }
    return {};
}

// The folders, read; one matrix and one build across them.
Result<std::vector<Folder>> readFolders(const std::vector<std::string>& dirs) {
    if (dirs.empty()) return badInput("needs one or more render folders (cavity_render --out DIR)");
    std::vector<Folder> folders;
    for (const auto& d : dirs) {
        CAVITY_ASSIGN(Folder f, readFolder(d));
        if (!folders.empty()) {
            const Folder& first = folders.front();
            if (f.m.matrix != first.m.matrix)
                return badInput(f.path + ": matrix " + f.m.matrix + ", but " + first.path + " has " + first.m.matrix +
                                " (judge one matrix at a time)");
            if (f.m.gitCommit != first.m.gitCommit)
                return badInput(f.path + ": rendered by build " + f.m.gitCommit + ", but " + first.path + " by build " +
                                first.m.gitCommit + " (render every shard with one build)");
            if (render::replacedJson(f.m.replaced) != render::replacedJson(first.m.replaced))
                return badInput(f.path + ": rendered with kernel sources " + core::jsonText(render::replacedJson(f.m.replaced)) + ", but " +
                                first.path + " with " + core::jsonText(render::replacedJson(first.m.replaced)) +
                                " (render every shard with the same --kernel-source)");
            if (measure::packagesJson(f.m.packages) != measure::packagesJson(first.m.packages))
                return badInput(f.path + ": rendered with kernel packages " + core::jsonText(measure::packagesJson(f.m.packages)) + ", but " +
                                first.path + " with " + core::jsonText(measure::packagesJson(first.m.packages)) +
                                " (render every shard with the same --kernels)");
        }
        folders.push_back(std::move(f));
    }
    return folders;
}

// The matrix as declared now, which every folder must have been rendered
// from, by this build.
Result<Matrix> renderedMatrix(const std::vector<Folder>& folders, const std::string& baselines) {
    const std::string matrices = (fs::path(baselines) / "matrices.json").string();
    CAVITY_ASSIGN(Matrix matrix, loadMatrix(matrices, folders.front().m.matrix));
    for (const auto& f : folders) {
        if (f.m.matrixHash != matrix.hash)
            return badInput(f.path + ": matrix " + f.m.matrix + " was rendered from another declaration (" + f.m.matrixHash +
                            "; " + matrices + " now gives " + matrix.hash + "): render it again");
        if (f.m.gitCommit != gitCommit())
            return badInput(f.path + ": rendered by build " + f.m.gitCommit + ", this cavity is build " + gitCommit() +
                            " (judge with the cavity of the build that rendered it, or render again)");
        // Shards of two selections: the configurations one selects and the
        // other's shard was to hold are judged by neither. (Whole folders of
        // two filters, one an API each, are judged together.)
        if ((f.m.shardCount > 1 || folders.front().m.shardCount > 1) && f.m.filter != folders.front().m.filter)
            return badInput(f.path + ": rendered with --filter '" + f.m.filter + "', " + folders.front().path +
                            " with '" + folders.front().m.filter + "' (shards of one selection are judged together)");
    }
    return matrix;
}

struct Item {
    const Folder* f;
    const render::ConfigEntry* c;
};

// The order `cavity gate` renders in: OpenGL first, then matrix order.
std::vector<Item> gateOrder(const std::vector<Folder>& folders) {
    std::vector<Item> items;
    for (const auto& f : folders)
        for (const auto& c : f.m.configs) items.push_back({&f, &c});
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
        return std::pair(a.c->api != "gl", a.c->index) < std::pair(b.c->api != "gl", b.c->index);
    });
    return items;
}

// The run's header: its shard when one folder is judged, the backends that
// did not start, and the longest render's time.
GateRun runHeader(const std::vector<Folder>& folders, const Matrix& matrix, double& rendered) {
    GateRun run;
    run.matrix = matrix.name;
    if (folders.size() == 1) {
        run.shardIndex = folders.front().m.shardIndex;
        run.shardCount = folders.front().m.shardCount;
    }
    run.filter = folders.front().m.filter;
    run.replaced = folders.front().m.replaced;
    run.packages = folders.front().m.packages;
    rendered = 0;
    for (const auto& f : folders) {
        rendered = std::max(rendered, f.m.seconds);
        for (const auto& e : f.m.backendErrors)
            if (std::find(run.backendErrors.begin(), run.backendErrors.end(), e.message) == run.backendErrors.end())
                run.backendErrors.push_back(e.message);
    }
    return run;
}

// One render of a folder as the gate's in-memory rendering, its stored
// images read back.
Result<render::Rendering> readRendering(const Item& item, const render::RenderEntry& entry, const RunConfig& config) {
    const auto& [f, c] = item;
    render::Rendering r;
    r.index = c->index;
    r.repetition = entry.repetition;
    r.config = config;
    r.id = c->id;
    r.key = c->key;
    if (auto d = f->m.devices.find(c->api); d != f->m.devices.end()) r.device = d->second;
    r.device.deviceName = c->device;
    r.error = entry.error;
    r.errorCode = entry.errorCode;
    r.deterministic = entry.deterministic;
    r.timings = entry.timings;
    for (const auto& i : entry.images) {
        r.digests[i.name] = i.stored.digest;
        if (i.judged) r.judged[i.name] = *i.judged;
        if (i.file.empty()) continue;
        CAVITY_ASSIGN(r.images[i.name], render::readImageFile((fs::path(f->dir) / i.file).string(), i.stored));
    }
    return r;
}

// One configuration's renders, in order: a later repetition that matches
// repetition 0 takes its check.
Result<std::vector<ConfigResult>> judgeItem(const Item& item, const std::vector<RunConfig>& all, const Judge& judge,
                                            Progress& progress, std::mutex& progressLock) {
    std::vector<ConfigResult> out;
    ConfigResult rep0;
    for (const auto& entry : item.c->renders) {
        CAVITY_ASSIGN(const render::Rendering r, readRendering(item, entry, all[item.c->index]));
        CAVITY_ASSIGN(ConfigResult res, judgeRendering(r, judge, entry.repetition ? &rep0 : nullptr));
        {
            std::lock_guard<std::mutex> lock(progressLock);
            progress.done(res.label() + " " + (res.passed() ? "pass" : "FAIL"), res.error.empty());
        }
        if (entry.repetition == 0) rep0 = res;
        out.push_back(std::move(res));
    }
    return out;
}

// Every configuration judged on as many threads as the machine has cores:
// reading, comparing and writing one configuration's images is independent
// of every other's. Image reads, which swap fd 2, take core::stderrLock()
// and so does every progress line. The results come in the items' order;
// the first error in that order wins.
Result<std::vector<std::vector<ConfigResult>>> judgeItems(const std::vector<Item>& items, const std::vector<RunConfig>& all,
                                                          const Judge& judge, Progress& progress) {
    std::vector<std::optional<Result<std::vector<ConfigResult>>>> results(items.size());
    std::atomic<size_t> next{0};
    std::mutex progressLock;
    auto work = [&] {
        for (size_t i = next++; i < items.size(); i = next++) results[i] = judgeItem(items[i], all, judge, progress, progressLock);
    };
    const size_t threads = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, std::max<size_t>(1, items.size()));
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    std::vector<std::vector<ConfigResult>> out;
    for (auto& r : results) {
        if (!*r) return r->error();
        out.push_back(std::move(**r));
    }
    return out;
}

// The folders hold every shard of their count, or exactly the ones --shards
// names: judging half a fleet's folders is not a verdict on the matrix.
Status checkShards(const std::vector<Folder>& folders, const std::string& told) {
    const int count = folders.front().m.shardCount;
    std::set<int> have;
    for (const auto& f : folders) {
        if (f.m.shardCount != count)
            return badInput(f.path + ": shard " + std::to_string(f.m.shardIndex) + "/" + std::to_string(f.m.shardCount) +
                            ", but " + folders.front().path + " is of " + std::to_string(count) + " shards");
        have.insert(f.m.shardIndex);
    }
    std::set<int> want;
    const std::string form = "--shards " + told + ": must be I[,J...]/N, shards of the folders' count " + std::to_string(count) +
                             " (e.g. 1/" + std::to_string(count) + ")";
    if (told.empty()) {
        for (int i = 0; i < count; ++i) want.insert(i);
    } else {
        const auto slash = told.find('/');
        if (slash == std::string::npos || told.substr(slash + 1) != std::to_string(count)) return badInput(form);
        std::stringstream list(told.substr(0, slash));
        for (std::string item; std::getline(list, item, ',');) {
            if (item.empty() || item.size() > 6 || item.find_first_not_of("0123456789") != std::string::npos) return badInput(form);
            const int i = std::stoi(item);
            if (i >= count) return badInput(form);
            if (!want.insert(i).second) return badInput("--shards " + told + ": shard " + item + " given twice");
        }
    }
    // At most 12 numbers, then how many more: the line stays one line.
    const auto text = [&](const std::set<int>& s) {
        std::string out;
        size_t n = 0;
        for (int i : s) {
            if (n++ == 12) {
                out += ",... (" + std::to_string(s.size() - 12) + " more)";
                break;
            }
            if (!out.empty()) out += ',';
            out += std::to_string(i);
        }
        out += '/';
        out += std::to_string(count);
        return out;
    };
    if (have == want) return {};
    std::set<int> missing, extra;
    std::set_difference(want.begin(), want.end(), have.begin(), have.end(), std::inserter(missing, missing.end()));
    std::set_difference(have.begin(), have.end(), want.begin(), want.end(), std::inserter(extra, extra.end()));
    if (!missing.empty() && told.empty())
        return badInput("the folders hold shards " + text(have) + "; shards " + text(missing) + " are missing (judge every " +
                        "shard's folder, or name the ones judged: --shards " + text(have) + ")");
    return badInput("the folders hold shards " + text(have) + ", --shards " + told + " names " + text(want));
}

}  // namespace

Result<GateRun> judgeFolders(const std::vector<std::string>& dirs, const JudgeOptions& o) {
    const std::string& baselines = o.baselines;
    const auto start = std::chrono::steady_clock::now();
    CAVITY_ASSIGN(const auto folders, readFolders(dirs));
    CAVITY_TRY(checkShards(folders, o.shards));
    CAVITY_ASSIGN(const Matrix matrix, renderedMatrix(folders, baselines));
    const auto all = matrix.expand();
    std::map<std::string, std::string> owner;
    CAVITY_ASSIGN(const auto approved, plan::loadApprovals((fs::path(baselines) / "approvals.json").string()));
    for (const auto& f : folders) CAVITY_TRY(checkEntries(f, all, owner, approved));
    for (const auto& f : folders) CAVITY_TRY(checkComplete(f, matrix));
    for (const auto& f : folders) CAVITY_TRY(checkFiles(f));
    std::vector<RunConfig> configs;
    for (const auto& f : folders)
        for (const auto& c : f.m.configs) configs.push_back(all[c.index]);
    CAVITY_ASSIGN(Judge judge, prepareJudge(baselines, configs, o.out, o.store));
    dropStaleReports(o.out);
    judge.enforceCpuBudgets = o.enforceCpuBudgets;
    const auto items = gateOrder(folders);
    double rendered = 0;
    GateRun run = runHeader(folders, matrix, rendered);
    size_t renders = 0;
    for (const auto& item : items) renders += item.c->renders.size();
    Progress progress(renders, o.quiet, "gate: ");
    CAVITY_ASSIGN(auto judged, judgeItems(items, all, judge, progress));
    for (auto& results : judged)
        for (auto& res : results) run.results.push_back(std::move(res));
    run.renderSeconds = rendered;
    run.seconds = rendered + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

}  // namespace cavity::gate
