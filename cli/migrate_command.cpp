// `cavity baselines migrate-digests`: approvals.json's FNV-1a digests
// rewritten as SHA-256 (core/digest.h), with each image filed in the store
// under its new name. Everything is found and checked before anything is
// written; the store only gains objects (the old ones stay, so an old
// approvals.json still reads), and approvals.json is replaced whole, last:
// killed at any point, it leaves the old file or the new one, and either
// passes the same images.
#include "cli.h"
#include "gate_outputs.h"
#include "core/digest.h"
#include "plan/approvals.h"
#include "plan/matrix.h"
#include "render/image_file.h"
#include "store/store.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

namespace cavity::cli {

namespace fs = std::filesystem;

namespace {

const CommandSpec& migrateSpec() {
    static const CommandSpec spec{
        "cavity baselines migrate-digests",
        "Rewrites every FNV-1a digest in approvals.json as the SHA-256 of the same pixels, and files each image in "
        "the image store under its SHA-256 digest. The pixels are found in the store (its fnv1a64/ objects), the "
        "baseline images, or the --from folders (any .f32z under them: render folders, gate runs), and each is checked "
        "against its FNV-1a digest first. Nothing is written unless every digest is found (or --keep-unmigrated).",
        {
            {"--baselines", "DIR", kBaselinesHelp},
            storeFlag(),
            storeCacheFlag(),
            {"--from", "DIR", "a render folder or gate run that holds images the store lacks (a fresh render of the "
                              "approved configurations); repeatable", "Options", true},
            {"--keep-unmigrated", "", "migrate what is found and keep the rest as FNV-1a (still read, with a warning)"},
            {"--drop-superseded", "", "drop an FNV-1a approval whose pixels are found nowhere when its slot (key, image, "
                                      "device class, API, stage) has a SHA-256 approval: an older image of it, which "
                                      "no render makes any more"},
        },
        "",
        "",
        "\nExit codes: 0 migrated (or nothing to migrate), 2 bad input, 5 the store cannot be reached, or an image "
        "was found nowhere, 6 an image does not match its digest.",
        {
            "cavity baselines migrate-digests",
            "cavity baselines migrate-digests --store https://store.example/refs",
            "cavity baselines migrate-digests --from out/render --keep-unmigrated",
            "cavity baselines migrate-digests --from out/render --drop-superseded",
        },
    };
    return spec;
}

// Where the pixels of one FNV-1a digest were found.
struct Found {
    std::string sha;      // their SHA-256 digest
    std::string bytes;    // the store object (an .f32z), when the store held them
    std::string path;     // else the file that holds them
};

Result<HostImage> readAny(const std::string& path) {
    if (fs::path(path).extension() != ".f32z") return readImage(path);
    std::ifstream f(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    return render::decodeImage(bytes, path);
}

// The store's object, checked against the FNV-1a digest it is filed under; a
// store that lacks it is not an error (the pixels may be elsewhere).
Result<bool> fromStore(store::ImageStore& s, const std::string& digest, Found& found) {
    auto bytes = s.getBytes(digest);
    if (!bytes) {
        if (store::isMissingObject(bytes.error())) return false;
        return bytes.error();
    }
    CAVITY_ASSIGN(const HostImage image, store::decodeObject(*bytes, digest, s.where() + "/" + store::objectPath(digest)));
    found = {core::imageDigest(image), std::move(*bytes), ""};
    return true;
}

// Each file among `paths` whose pixels have a wanted FNV-1a digest.
Status fromFiles(const std::vector<std::string>& paths, std::map<std::string, Found>& found,
                 const std::set<std::string>& wanted) {
    for (const auto& p : paths) {
        if (found.size() == wanted.size()) return {};
        auto image = readAny(p);
        if (!image) continue;   // not an image of ours: another file in the folder
        const std::string fnv = core::legacyImageDigest(*image);
        if (wanted.count(fnv) && !found.count(fnv)) found[fnv] = {core::imageDigest(*image), "", p};
    }
    return {};
}

struct MigrateFlags {
    std::string root;
    store::StoreOptions store;
    std::vector<std::string> from;
    bool keep = false, dropSuperseded = false;
};

Result<MigrateFlags> parseMigrate(const ParsedFlags& p) {
    MigrateFlags f;
    f.keep = p.has("--keep-unmigrated");
    f.dropSuperseded = p.has("--drop-superseded");
    for (const auto& [flag, v] : p.values) {
        if (flag == "--baselines") f.root = v;
        else if (flag == "--store") f.store.location = v;
        else if (flag == "--store-cache") f.store.cache = v;
        else if (flag == "--from") {
            std::error_code ec;
            if (!fs::is_directory(v, ec)) return badInput("--from " + v + ": not a folder (a render folder or gate run)");
            f.from.push_back(v);
        }
    }
    if (f.root.empty()) {
        CAVITY_ASSIGN(f.root, defaultBaselines());
    }
    store::fillDefault(f.store, f.root);
    return f;
}

// Every legacy digest's pixels: the store first, then the baseline images,
// then the --from folders.
Result<std::map<std::string, Found>> findPixels(const plan::Approvals& approvals, const MigrateFlags& f,
                                                store::ImageStore& s) {
    std::set<std::string> wanted;
    std::vector<std::string> baselineFiles;
    for (const auto& a : approvals.entries) {
        if (!core::isLegacyDigest(a.digest)) continue;
        wanted.insert(a.digest);
        for (const auto& ci : plan::checkedImages())
            if (ci.name == a.image) baselineFiles.push_back((fs::path(f.root) / "images" / a.key / (a.image + ci.extension)).string());
    }
    std::map<std::string, Found> found;
    for (const auto& d : wanted) {
        Found one;
        CAVITY_ASSIGN(const bool there, fromStore(s, d, one));
        if (there) found[d] = std::move(one);
    }
    CAVITY_TRY(fromFiles(baselineFiles, found, wanted));
    for (const auto& dir : f.from) {
        std::vector<std::string> files;
        for (const auto& e : fs::recursive_directory_iterator(dir))
            if (e.is_regular_file() && e.path().extension() == ".f32z") files.push_back(e.path().string());
        CAVITY_TRY(fromFiles(files, found, wanted));
    }
    return found;
}

// Drops each FNV-1a approval whose pixels were found nowhere and whose slot
// has a positive SHA-256 approval (or one that migrates): an older image of that configuration on
// that device, which no current render makes, so nothing can migrate it.
int dropSuperseded(plan::Approvals& approvals, const std::map<std::string, Found>& found) {
    auto slot = [](const plan::Approval& a) {
        return a.key + "\n" + a.image + "\n" + a.deviceClass + "\n" + a.api + "\n" + a.stage;
    };
    std::set<std::string> current;
    for (const auto& a : approvals.entries)
        if (a.positive && (!core::isLegacyDigest(a.digest) || found.count(a.digest))) current.insert(slot(a));
    const size_t before = approvals.entries.size();
    std::erase_if(approvals.entries, [&](const plan::Approval& a) {
        return core::isLegacyDigest(a.digest) && !found.count(a.digest) && current.count(slot(a));
    });
    const int dropped = int(before - approvals.entries.size());
    approvals.legacy -= dropped;
    return dropped;
}

}  // namespace

int migrateCommand(const std::vector<std::string>& argv) {
    const std::string program = "cavity baselines migrate-digests";
    auto parsed = parseFlags(migrateSpec(), argv);
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    auto f = parseMigrate(*parsed);
    if (!f) return fail(program, f.error());
    const std::string path = (fs::path(f->root) / "approvals.json").string();
    // loadApprovals reads a missing file as none; here that would be
    // "nothing to do" about a folder that is not there.
    if (std::error_code ec; !fs::is_regular_file(path, ec))
        return fail(program, badInput("--baselines " + f->root + ": no approvals.json in it" +
                                      (fs::is_directory(f->root, ec) ? "" : " (no such folder)")));
    auto approvals = plan::loadApprovals(path);
    if (!approvals) return fail(program, approvals.error());
    if (approvals->legacy == 0) {
        std::cout << path << ": every digest is SHA-256 already; nothing to do\n";
        return 0;
    }
    auto s = store::openStore(f->store);
    if (!s) return fail(program, s.error());
    auto found = findPixels(*approvals, *f, **s);
    if (!found) return fail(program, found.error());
    const int dropped = f->dropSuperseded ? dropSuperseded(*approvals, *found) : 0;
    int missing = 0;
    std::string first;
    for (const auto& a : approvals->entries)
        if (core::isLegacyDigest(a.digest) && !found->count(a.digest)) {
            if (!missing++) first = a.key + " " + a.image + " " + a.digest + " (" + a.deviceClass + ")";
        }
    if (missing && !f->keep)
        return fail(program, unreachable(std::to_string(missing) + " of " + std::to_string(approvals->legacy) +
                                         " FNV-1a approvals have pixels in neither the store (" + (*s)->where() +
                                         "), the baseline images nor --from, first " + first +
                                         ": nothing written (--from a fresh render of them, or --keep-unmigrated)"));
    // The store gains each image under its SHA-256 name; then approvals.json.
    for (const auto& [fnv, one] : *found) {
        // An object already there counts only if it is the image: one that
        // is damaged is written again.
        auto there = (*s)->has(one.sha);
        if (!there) return fail(program, there.error());
        if (*there && store::getImage(**s, one.sha)) continue;
        std::string bytes = one.bytes;
        if (bytes.empty()) {
            auto image = readAny(one.path);
            if (!image) return fail(program, image.error());
            bytes = render::encodeImage(*image);
        }
        if (auto st = (*s)->put(one.sha, bytes); !st) return fail(program, st.error());
    }
    int migrated = 0;
    for (auto& a : approvals->entries)
        if (auto it = found->find(a.digest); core::isLegacyDigest(a.digest) && it != found->end()) {
            a.digest = it->second.sha;
            ++migrated;
        }
    if (auto st = plan::saveApprovals(path, *approvals); !st) return fail(program, st.error());
    std::cout << "migrated " << migrated << " approvals (" << found->size() << " images) to SHA-256 in " << path
              << "; the store " << (*s)->where() << " holds each under its new digest\n";
    if (dropped) std::cout << "dropped " << dropped << " FNV-1a approvals superseded by a SHA-256 approval of their slot\n";
    if (missing) std::cout << missing << " approvals kept their FNV-1a digest: their pixels were found nowhere\n";
    return 0;
}

}  // namespace cavity::cli
