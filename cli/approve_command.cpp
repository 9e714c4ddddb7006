// `cavity baselines approve`: the digests of a judged run's images, added to
// baselines/approvals.json for the device class they were rendered on, as
// positives (the next identical render passes by digest, nothing computed)
// or negatives (known bad: fails at once), with who, when and why.
#include "gate_outputs.h"
#include "core/json_file.h"
#include "plan/approvals.h"
#include "gate/gate.h"
#include "measure/results.h"
#include "images/image_io.h"
#include "render/image_file.h"
#include "render/render_manifest.h"
#include "store/store.h"

#include <algorithm>
#include <map>
#include <set>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>

namespace cavity::cli {

namespace fs = std::filesystem;

// gate.json names its images as the gate wrote them, relative to where it
// ran (or absolute). Read from `dir`, they are `dir`'s own images/: a gate
// folder downloaded from CI, moved, or named from another directory is read
// whole, and never the images of the folder it was copied from.
std::string inFolder(const std::string& dir, const std::string& recorded) {
    const auto at = recorded.rfind("images/");
    if (recorded.empty() || at == std::string::npos || (at > 0 && recorded[at - 1] != '/')) return recorded;
    return (fs::path(dir) / recorded.substr(at)).string();
}

Result<gate::GateRun> loadGateJson(const std::string& dir) {
    const std::string path = (fs::path(dir) / "gate.json").string();
    if (!fs::exists(path)) return badInput(path + ": cannot be read (run `cavity gate --out " + dir + "` first)");
    CAVITY_ASSIGN(const nlohmann::json j, readJsonFile(path));
    CAVITY_ASSIGN(gate::GateRun run, gate::fromJson(j, path));
    for (auto& r : run.results)
        for (auto& i : r.images)
            for (std::string* p : {&i.newExact, &i.newPng, &i.diffPng})
                *p = inFolder(dir, *p);
    return run;
}

namespace {

const CommandSpec& approveSpec() {
    static const CommandSpec spec{
        "cavity baselines approve",
        "Approves the images of a judged gate run by digest for the device class each was rendered on "
        "(baselines/approvals.json): a later render with the same digest passes at once, with no metric computed. "
        "With --negative, marks them known bad instead: a render with that digest fails at once, on any device.",
        {
            {"--from", "DIR", "a gate output folder (gate.json), or a render folder of cavity_render (manifest.json: its "
                              "digests, no images needed) (default out/gate)"},
            {"--why", "TEXT", "why these images are right (or, with --negative, wrong); recorded (required)"},
            {"--filter", "REGEX", "only the configurations whose id matches (default: every one that rendered)"},
            {"--negative", "", "mark the digests known bad instead of approving them"},
            {"--with-kernel-source", "", "the gate run replaced kernel sources (--kernel-source): also copy each file over "
                                         "its kernels/NAME or its package's file, so that the tree renders what is approved"},
            {"--by", "NAME", "who approves (default: $USER)"},
            {"--baselines", "DIR", "folder with approvals.json (default: baselines/ of the checkout found from the working "
                                   "directory up, else of the source tree this binary was built from)"},
            {"--store", "DIR|URL", "the image store the approved images are put into, under their digest (default "
                                   "$CAVITY_STORE, else <baselines>/store; docs/store.md)"},
        },
        "",
        "",
        "",
        {
            "cavity baselines approve --from out/gate --why 'H200, driver 580: first references'",
            "cavity baselines approve --from out/gate --filter '/alchemy_fast/' --negative --why 'bad pick'",
            "cavity baselines approve --from out/render --store https://store.example/refs --why 'driver 580'",
        },
    };
    return spec;
}

struct ApproveFlags {
    std::string from = "out/gate", why, by, root, store;
    std::optional<std::regex> filter;
    bool negative = false;
    bool withKernelSource = false;   // copy a --kernel-source edit over its file with the approvals
};

Result<ApproveFlags> parseApprove(const ParsedFlags& p) {
    ApproveFlags f;
    f.negative = p.has("--negative");
    f.withKernelSource = p.has("--with-kernel-source");
    for (const auto& [flag, v] : p.values) {
        if (flag == "--from") f.from = v;
        else if (flag == "--why") f.why = v;
        else if (flag == "--by") f.by = v;
        else if (flag == "--baselines") f.root = v;
        else if (flag == "--store") f.store = v;
        else if (flag == "--filter") {
            CAVITY_ASSIGN(f.filter, parseFilter(flag, v));
        }
    }
    if (f.why.find_first_not_of(" \t\r\n") == std::string::npos)
        return badInput(f.why.empty() ? std::string("--why: required (what makes these images right, or with --negative wrong)")
                                      : "--why '" + f.why + "': blanks only (say what makes these images right, or with "
                                                            "--negative wrong)");
    for (const char* var : {"USER", "LOGNAME"})
        if (f.by.empty() && std::getenv(var) && *std::getenv(var)) f.by = std::getenv(var);
    if (f.by.empty()) f.by = "unknown";
    if (f.root.empty()) {
        CAVITY_ASSIGN(f.root, defaultBaselines());
    }
    return f;
}

// The approvals a run adds: every image of every selected configuration that
// rendered, once per key, image, digest and device class.
// An approved image whose pixels this run holds, for the store: a file of
// the gate's output (`stored` empty) or of a render folder.
struct Pixels {
    std::string digest, path;
    render::StoredImage stored;
};

Result<size_t> addApprovals(plan::Approvals& a, const gate::GateRun& run, const ApproveFlags& f, std::vector<Pixels>& pixels,
                           size_t& selected, size_t& rendered) {
    const std::string when = utcTimestamp();
    size_t added = 0;
    for (const auto& r : run.results) {
        if (f.filter && !std::regex_search(r.id, *f.filter)) continue;
        ++selected;
        if (!r.error.empty()) continue;
        ++rendered;
        if (r.device.empty())
            return badInput(f.from + "/gate.json: " + r.id + ": no device recorded (a digest is approved for the device "
                            "class it was rendered on)");
        const auto parts = r.id.substr(r.key.size() + 1);   // "vk/compute"
        const std::string api = parts.substr(0, parts.find('/')), stage = parts.substr(parts.find('/') + 1);
        for (const auto& i : r.images) {
            plan::Approval x{r.key, i.image, i.digest, !f.negative, plan::deviceClass(r.device), api, stage,
                             r.driver, f.by, when, f.why};
            const auto same = [&](const plan::Approval& e) {
                return e.key == x.key && e.image == x.image && e.digest == x.digest && e.positive == x.positive &&
                       e.deviceClass == x.deviceClass;
            };
            if (i.digest.empty()) continue;
            // Into the store whether or not the digest was approved before:
            // approving again is how an empty store is filled.
            if (!i.newExact.empty()) {
                // Beside the exact image the judge wrote its float bits
                // (gate_judge.cpp): those are what the digest is of.
                const fs::path bits = fs::path(i.newExact).replace_extension(".f32z");
                std::error_code ec;
                pixels.push_back({i.digest, fs::exists(bits, ec) ? bits.string() : i.newExact, {}});
            }
            if (std::any_of(a.entries.begin(), a.entries.end(), same)) continue;
            a.entries.push_back(std::move(x));
            ++added;
        }
    }
    return added;
}

// The approvals a render folder adds: the digests its manifest records, for
// the device each configuration rendered on. A configuration whose
// repetitions disagree is left out (a digest approves one image exactly).
Result<size_t> addRenderApprovals(plan::Approvals& a, const std::string& dir, const ApproveFlags& f, size_t& skipped,
                                  std::vector<Pixels>& pixels, size_t& selected, size_t& rendered) {
    const std::string path = (fs::path(dir) / "manifest.json").string();
    CAVITY_ASSIGN(const auto j, readJsonFile(path));
    CAVITY_ASSIGN(const render::RenderManifest m, render::parseManifest(j, path));
    const std::string when = utcTimestamp();
    size_t added = 0;
    for (const auto& c : m.configs) {
        if (f.filter && !std::regex_search(c.id, *f.filter)) continue;
        ++selected;
        if (c.device.empty())
            return badInput(path + ": " + c.id + ": no device recorded (a digest is approved for the device class it was "
                            "rendered on)");
        std::map<std::string, std::set<std::string>> digests;   // image -> digests over the repetitions
        bool failed = false;
        std::map<std::string, Pixels> files;   // image -> its file, where the folder holds one
        for (const auto& r : c.renders) {
            failed |= !r.error.empty();
            for (const auto& i : r.images) {
                digests[i.name].insert(i.stored.digest);
                if (!i.file.empty()) files[i.name] = {i.stored.digest, (fs::path(dir) / i.file).string(), i.stored};
            }
        }
        const bool agree = std::all_of(digests.begin(), digests.end(), [](const auto& d) { return d.second.size() == 1; });
        if (failed || !agree || digests.empty()) {
            ++skipped;
            continue;
        }
        ++rendered;
        const auto device = m.devices.find(c.api);
        const std::string stage = c.id.substr(c.id.rfind('/') + 1);
        for (const auto& [image, ds] : digests) {
            plan::Approval x{c.key, image, *ds.begin(), !f.negative, plan::deviceClass(c.device), c.api, stage,
                             device == m.devices.end() ? "" : device->second.driver, f.by, when, f.why};
            const auto same = [&](const plan::Approval& e) {
                return e.key == x.key && e.image == x.image && e.digest == x.digest && e.positive == x.positive &&
                       e.deviceClass == x.deviceClass;
            };
            if (const auto file = files.find(image); file != files.end()) pixels.push_back(file->second);
            if (std::any_of(a.entries.begin(), a.entries.end(), same)) continue;
            a.entries.push_back(std::move(x));
            ++added;
        }
    }
    return added;
}

// Every approved image this run holds, put into the store under its digest
// (each checked to be the image approved); approvals.json is written only
// after all of them are there.
// The pixels of one approved image, as the run holds them.
Result<HostImage> readPixels(const Pixels& p) {
    if (p.stored.digest.empty() && fs::path(p.path).extension() == ".f32z") {
        std::ifstream f(p.path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        return render::decodeImage(bytes, p.path);
    }
    if (p.stored.digest.empty()) return readImage(p.path);
    return render::readImageFile(p.path, p.stored);
}

// Every approved image this run holds, put into the store under its digest.
// Each is checked to be the image approved before the first is put, so that
// a refusal leaves the store as it was; approvals.json is written only after
// all of them are there.
Result<size_t> putImages(const std::vector<Pixels>& pixels, const ApproveFlags& f) {
    store::StoreOptions so;
    so.location = f.store;
    store::fillDefault(so, f.root);
    CAVITY_ASSIGN(auto target, store::openStore(so));
    std::vector<const Pixels*> unique;
    std::set<std::string> seen;
    for (const auto& p : pixels)
        if (seen.insert(p.digest).second) unique.push_back(&p);
    for (const Pixels* p : unique) {
        CAVITY_ASSIGN(const HostImage image, readPixels(*p));
        if (const std::string digest = store::imageDigest(image); digest != p->digest)
            return badInput(p->path + ": its pixels have digest " + digest + ", the run recorded " + p->digest);
    }
    for (const Pixels* p : unique) {
        CAVITY_ASSIGN(const bool there, target->has(p->digest));
        if (there) continue;
        CAVITY_ASSIGN(const HostImage image, readPixels(*p));
        CAVITY_ASSIGN(const std::string digest, store::putImage(*target, image));
        if (digest != p->digest)
            return badInput(p->path + ": its pixels have digest " + digest + ", the run recorded " + p->digest);
    }
    return unique.size();
}

}  // namespace

int approveCommand(const std::vector<std::string>& argv) {
    const std::string program = "cavity baselines approve";
    auto parsed = parseFlags(approveSpec(), argv);
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    auto f = parseApprove(*parsed);
    if (!f) return fail(program, f.error());
    const std::string path = (fs::path(f->root) / "approvals.json").string();
    // Checked before anything is put into the store.
    if (std::error_code ec; !fs::is_directory(f->root, ec))
        return fail(program, badInput("--baselines " + f->root + ": no such folder"));
    auto approvals = plan::loadApprovals(path);
    if (!approvals) return fail(program, approvals.error());
    size_t added = 0, skipped = 0, selected = 0, rendered = 0;
    SourceCopies sources;        // --with-kernel-source: the edits the approved images show
    gate::GateRun replacedRun;
    std::vector<Pixels> pixels;
    std::error_code ec;
    if (!fs::exists(fs::path(f->from) / "gate.json", ec) && fs::exists(fs::path(f->from) / "manifest.json", ec)) {
        auto n = addRenderApprovals(*approvals, f->from, *f, skipped, pixels, selected, rendered);
        if (!n) return fail(program, n.error());
        added = *n;
    } else {
        auto run = loadGateJson(f->from);
        if (!run) return fail(program, run.error());
        // Digests of an edit that kernels/ does not hold would pass the
        // next run of the edit and fail the tree's own (baselines update
        // --with-kernel-source copies the edit in with the images).
        if (!f->negative) {
            auto copies = kernelSourceCopies(*run, f->root, f->from, f->withKernelSource);
            if (!copies) return fail(program, copies.error());
            sources = std::move(*copies);
            replacedRun = *run;
        }
        auto n = addApprovals(*approvals, *run, *f, pixels, selected, rendered);
        if (!n) return fail(program, n.error());
        added = *n;
    }
    if (selected == 0) {
        std::string what = "--from " + f->from + ": no configuration";
        for (const auto& [flag, v] : parsed->values)
            if (flag == "--filter") what = "--filter " + v + ": matches no configuration of " + f->from;
        return fail(program, badInput(what + " (nothing approved, approvals.json left as it was)"));
    }
    if (rendered == 0)
        return fail(program, badInput("--from " + f->from + ": no image to approve (every selected configuration failed "
                                      "to render, or its repetitions disagree); nothing approved, approvals.json left "
                                      "as it was"));
    auto stored = putImages(pixels, *f);
    if (!stored) return fail(program, stored.error());
    if (auto st = plan::saveApprovals(path, *approvals); !st) return fail(program, st.error());
    if (auto st = copyKernelSources(sources, replacedRun); !st) return fail(program, st.error());
    // Images with the same pixels (both APIs alike, say) share one object.
    std::cout << added << " image digests " << (f->negative ? "marked known bad" : "approved") << " in " << path << "; "
              << *stored << " distinct images in the store\n";
    if (skipped)
        std::cout << skipped << " configurations left out: a render error, or repetitions with different images\n";
    return 0;
}

}  // namespace cavity::cli
