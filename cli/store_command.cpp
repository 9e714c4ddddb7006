// `cavity store check`: every image approved for a device class fetched from
// the image store and checked against its digest, as the judge would fetch
// it. Run it after approving from another machine, before going offline (it
// fills an HTTP store's cache), or to audit a store.
#include "cli.h"
#include "plan/approvals.h"
#include "store/store.h"

#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <set>

namespace cavity::cli {

namespace fs = std::filesystem;

namespace {

const CommandSpec& checkSpec() {
    static const CommandSpec spec{
        "cavity store check",
        "Fetches every image approved as a positive in approvals.json from the image store and checks that its pixels "
        "have the digest it is filed under; an HTTP store's objects land in its cache.",
        {
            {"--baselines", "DIR", "folder with approvals.json (default: baselines/ of the checkout)"},
            storeFlag(),
            storeCacheFlag(),
            {"--class", "NAME", "only the images approved for this device class (\"nvidia-h200\")"},
            {"--filter", "REGEX", "only the baseline keys that match (searched)"},
        },
        "",
        "",
        "\nExit codes: 0 every image there and whole, 2 bad input, 5 the store cannot be reached or lacks an image, "
        "6 an image does not match its digest.",
        {
            "cavity store check --class llvmpipe --filter '^corner/alchemy_fast/n16/b4/full/160x90$'",
            "cavity store check --store https://store.example/refs --filter '^corner/alchemy_fast/n16/b4/full/160x90$'",
        },
    };
    return spec;
}

}  // namespace

int storeCommand(const std::vector<std::string>& argv) {
    const std::string program = "cavity store check";
    if (!argv.empty() && (argv[0] == "--help" || argv[0] == "-h")) {
        std::cout << "Usage: cavity store check [OPTIONS]\n"
                     "  check   fetch every approved image from the image store and check its digest\n"
                     "`cavity store check --help` lists its flags.\n";
        return 0;
    }
    if (argv.empty() || argv[0] != "check") {
        std::cerr << "cavity store: " << (argv.empty() ? "needs a subcommand" : "unknown subcommand '" + argv[0] + "'")
                  << " (check); see cavity store check --help\n";
        return 2;
    }
    auto parsed = parseFlags(checkSpec(), {argv.begin() + 1, argv.end()});
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    std::string root, cls, filterText;
    store::StoreOptions so;
    std::optional<std::regex> filter;
    for (const auto& [flag, v] : parsed->values) {
        if (flag == "--baselines") root = v;
        else if (flag == "--store") so.location = v;
        else if (flag == "--store-cache") so.cache = v;
        else if (flag == "--class") cls = v;
        else if (flag == "--filter") {
            auto f = parseFilter(flag, v);
            if (!f) return fail(program, f.error());
            filter = *f;
            filterText = v;
        }
    }
    if (root.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail(program, found.error());
        root = *found;
    }
    // loadApprovals reads a missing file as none: here that is a mistake.
    if (std::error_code ec; !fs::is_regular_file(fs::path(root) / "approvals.json", ec))
        return fail(program, badInput("--baselines " + root + ": no approvals.json in it" +
                                      (fs::is_directory(root, ec) ? "" : " (no such folder)")));
    auto approvals = plan::loadApprovals((fs::path(root) / "approvals.json").string());
    if (!approvals) return fail(program, approvals.error());
    store::fillDefault(so, root);
    auto s = store::openStore(so);
    if (!s) return fail(program, s.error());
    std::set<std::string> digests;
    std::map<std::string, int> perClass;
    for (const auto& a : approvals->entries) {
        if (!a.positive || (!cls.empty() && a.deviceClass != cls) || (filter && !std::regex_search(a.key, *filter))) continue;
        if (digests.insert(a.digest).second) ++perClass[a.deviceClass];
    }
    if (digests.empty())
        return fail(program, badInput("no approved image matches (--class '" + cls + "', --filter '" + filterText + "') in " +
                                      root + "/approvals.json"));
    for (const auto& d : digests) {
        auto image = store::getImage(**s, d);
        if (!image) return fail(program, image.error());
    }
    for (const auto& [c, n] : perClass) std::cout << c << ": " << n << " images\n";
    std::cout << digests.size() << " approved images in " << (*s)->where() << ", each with the digest it is filed under";
    // An HTTP store's objects already in its cache are read from there (they
    // were checked when fetched): this is not an audit of the server's copy.
    const bool http = (*s)->where().rfind("http", 0) == 0;
    std::cout << (http ? " (objects already in the cache were read from it, not fetched again)" : "") << "\n";
    return 0;
}

}  // namespace cavity::cli
