// `cavity baselines update`: a gate run's new images accepted as the
// baselines, all or nothing (harness/gate/baseline_update.h).
#include "gate/baseline_update.h"
#include "gate_outputs.h"
#include "core/digest.h"
#include "core/json_file.h"
#include "package/package.h"
#include "render/image_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

namespace cavity::cli {

namespace fs = std::filesystem;

namespace {

const CommandSpec& updateSpec() {
    static const CommandSpec spec{
        "cavity baselines update",
        "Accepts a gate run's new images as baselines: without --filter the configurations that failed, with it "
        "every image of the configurations it selects. All or nothing.",
        {
            {"--from", "DIR", "a gate output folder with gate.json (default out/gate)"},
            {"--filter", "REGEX", "take the configurations whose id matches"},
            {"--baselines", "DIR", kBaselinesHelp},
            {"--with-kernel-source", "", "the run replaced kernel sources (--kernel-source): also copy each file over its "
                                         "kernels/NAME, so that the tree renders what the baselines show"},
        },
        "",
        "",
        "",
        {
            "cavity baselines update --from out/gate",
            "cavity baselines update --from out/gate --filter '^corner/alchemy/'",
            "cavity baselines update --from out/gate --with-kernel-source",
        },
    };
    return spec;
}

// What to do when configurations failed on time budgets alone: images are
// not what a baseline update changes.
std::string budgetOnlyHint(const gate::GateRun& run, bool filtered, const std::string& from, const std::string& root) {
    int budgetOnly = 0;
    std::string device;
    for (const auto& r : run.results)
        if (r.error.empty() && r.imagesPassed() && !r.timingPassed()) {
            ++budgetOnly;
            device = r.device;
        }
    if (budgetOnly == 0 || filtered) return "";
    // The entry the gate read the device's budgets from (the first whose
    // pattern its name holds), so that the script updates that one, in the
    // budgets.json of these baselines.
    const std::string budgets = (fs::path(root) / "budgets.json").string();
    std::string pattern = device;
    if (const auto loaded = gate::loadBudgets(budgets))
        if (const auto* entry = loaded->entryFor(device)) pattern = entry->pattern;
    return std::to_string(budgetOnly) + " configurations failed on time budgets only (every image passed): budgets are " +
           "not images; update them with `python3 scripts/update_budgets.py " + (fs::path(from) / "gate.json").string() +
           " --pattern '" + pattern + "' --budgets " + budgets + "` (docs/gate.md, \"Time budgets\")";
}

}  // namespace

// The files a run rendered in place of kernels/ (--kernel-source), each
// read and checked to be what was rendered, with where it goes in the tree
// beside `root`. A run with replaced sources is refused without
// --with-kernel-source: its images are not what the tree renders, and
// accepting them alone would leave tree and baselines disagreeing.
Result<SourceCopies> kernelSourceCopies(const gate::GateRun& run, const std::string& root, const std::string& from,
                                        bool take) {
    // A package edited since the gate: its baselines would show images its
    // files no longer render, and the next gate would fail them.
    for (const auto& p : run.packages) {
        const auto now = measure::packagesUsed(std::set<std::string>{p.name});
        if (now.empty())
            return badInput("--from " + from + ": judged kernel package " + p.name + " from " + p.folder +
                            ", which is not loaded: load it with --kernels " + p.folder);
        if (now[0].digest != p.digest)
            return badInput("--from " + from + ": judged kernel package " + p.name + " at " + p.digest + ", and its files (" +
                            now[0].folder + ") are now " + now[0].digest + ": run the gate again, then accept its images");
    }
    SourceCopies out;
    if (run.replaced.empty()) return out;
    std::string names;
    for (const auto& r : run.replaced) names += (names.empty() ? "" : ", ") + kernels::sourceLabel(r.name);
    if (!take)
        return badInput("--from " + from + ": rendered with " + names + " replaced (--kernel-source): its images are "
                        "not what those files render; pass --with-kernel-source to copy the edits over them with the "
                        "baselines, or copy them yourself and run the gate again");
    // An edit that did not render everywhere (a compile error, say) is not
    // one the baselines can show: copying it would replace a working file.
    for (const auto& r : run.results)
        if (!r.error.empty())
            return badInput("--with-kernel-source: " + r.id + " did not render with the edit (" + r.error.substr(0, 100) +
                            "); nothing copied, no baseline changed");
    std::error_code ec;
    const fs::path tree = fs::absolute(root, ec).lexically_normal().parent_path() / "kernels";
    for (const auto& r : run.replaced) {
        // A file of the tree goes to kernels/; a loaded package's from disk
        // to its own file, where the package lives.
        const std::string label = kernels::sourceLabel(r.name);
        const bool inTree = !kernels::packageSource(r.name);
        const fs::path target = inTree ? tree / r.name : fs::path(label);
        if (!fs::is_regular_file(target, ec))
            return badInput("--with-kernel-source: " + label + " is not a file" +
                            (inTree ? " of " + tree.string() + ", the kernels/ beside --baselines " + root +
                                          " (a built-in kernel's edit goes to the source tree cavity is built from: "
                                          "give that tree's baselines/, or copy the edit there yourself)"
                                    : std::string()));
        std::ifstream in(r.file, std::ios::binary);
        if (!in) return badInput("--with-kernel-source: " + r.file + " (for " + label + "): cannot be read");
        std::string text((std::istreambuf_iterator<char>(in)), {});
        if (const std::string digest = core::digestText(core::fnv1a64(text.data(), text.size())); digest != r.digest)
            return badInput("--with-kernel-source: " + r.file + " changed since the run (digest " + digest +
                            ", the run rendered " + r.digest + "): run the gate again");
        out[target] = {r.file, std::move(text)};
    }
    return out;
}

// Writes what kernelSourceCopies found, and says where the edits now live.
Status copyKernelSources(const SourceCopies& copies, const gate::GateRun& run) {
    for (const auto& [target, copy] : copies) {
        CAVITY_TRY(writeFileAtomically(target.string(), copy.second));
        std::cout << "copied " << copy.first << " over " << target.string() << "\n";
    }
    const bool builtIn = std::any_of(run.replaced.begin(), run.replaced.end(),
                                     [](const auto& r) { return !kernels::packageSource(r.name); });
    if (!copies.empty())
        std::cout << (builtIn ? "kernels/ now holds the edits the baselines show; rebuild cavity (built-in kernels are "
                                "compiled in) and commit both\n"
                              : "the packages now hold the edits the baselines show (they load at run time); commit "
                                "both\n");
    return {};
}

namespace {
int updateCommand(const std::vector<std::string>& argv);

// The new image beside a gate.json is the one that gate judged: its float
// bits (written before the image file, gate_judge.cpp) have the digest
// gate.json records. A gate killed after it began writing images, and
// before its gate.json, leaves files the older gate.json does not describe.
Status judgedPixels(const std::string& newExact, const std::string& digest, const std::string& from) {
    const fs::path bits = fs::path(newExact).replace_extension(".f32z");
    std::ifstream in(bits, std::ios::binary);
    if (!in || digest.empty()) return {};   // an output written before the bits were kept
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    CAVITY_ASSIGN(const HostImage image, render::decodeImage(bytes, bits.string()));
    if (const std::string now = core::imageDigestLike(image, digest); now != digest)
        return badInput("--from " + from + ": " + bits.string() + " has digest " + now + ", not the " + digest +
                        " its gate.json judged (a gate into that folder was interrupted): run the gate again");
    return {};
}
}  // namespace

int baselinesCommand(const std::vector<std::string>& argv) {
    if (!argv.empty() && (argv[0] == "--help" || argv[0] == "-h")) {
        std::cout << "usage: cavity baselines update|approve|migrate-digests [flags]   (see cavity baselines update "
                     "--help, cavity baselines approve --help, cavity baselines migrate-digests --help)\n";
        return 0;
    }
    if (!argv.empty() && argv[0] == "approve") return approveCommand({argv.begin() + 1, argv.end()});
    if (!argv.empty() && argv[0] == "migrate-digests") return migrateCommand({argv.begin() + 1, argv.end()});
    if (argv.empty() || argv[0] != "update")
        return fail("cavity baselines", badInput("'" + (argv.empty() ? std::string() : argv[0]) +
                                                 "': usage: cavity baselines update|approve|migrate-digests [flags]"));
    return updateCommand(argv);
}

namespace {

// A selection of only configurations that errored (a filter's, or without
// one every failure: a kernel that does not compile) accepts nothing:
// "0 baseline files updated" would read as if they were accepted.
Status onlyErrored(const gate::GateRun& run, const std::optional<std::regex>& filter, const std::string& filterText,
                   const std::string& from, bool nothingWritten) {
    if (!nothingWritten) return {};
    std::vector<std::string> errored;
    for (const auto& r : run.results)
        if ((filter ? std::regex_search(r.id, *filter) : r.verdict() != "pass") && !r.error.empty())
            errored.push_back(r.id + " (" + r.error.substr(0, 80) + ")");
    if (errored.empty()) return {};
    return badInput((filter ? "--filter " + filterText : "--from " + from) + ": " + std::to_string(errored.size()) +
                    " selected configurations rendered no image, e.g. " + errored[0] +
                    "; nothing updated, the baselines left as they were (mend the error and gate again)");
}

// Without a filter, what failed the gate: an expected failure or a known
// flake is not accepted as the new baseline by default. With the edits
// copied into the tree (--with-kernel-source), the configurations they
// changed within tolerance too: else the tree would render images the
// baselines do not hold, and every later gate would read "changed".
bool selectedForUpdate(const gate::ConfigResult& r, const std::optional<std::regex>& filter, bool takeChanged) {
    return filter ? std::regex_search(r.id, *filter) : r.verdict() == "fail" || (takeChanged && r.changed());
}

// The baseline files configuration r's images replace, and the lines that
// say so.
Status addWrites(const gate::ConfigResult& r, bool filtered, bool takeChanged, const std::string& from,
                 const std::string& root, std::vector<gate::BaselineWrite>& writes, std::vector<std::string>& said) {
    for (const auto& i : r.images) {
        // A selected configuration rewrites the images that failed (all of
        // them when chosen by --filter): passing ones keep their bytes.
        if (!filtered && i.passed() && !(takeChanged && i.changed())) continue;
        // Judged against an approved image of the device's class: the gate
        // compares with that reference before any baseline file, so writing
        // one would change nothing the next gate sees.
        if (i.baseline.rfind("store:", 0) == 0)
            return badInput("--from " + from + ": " + r.id + " " + i.image + " was judged against an approved " +
                            "image of its device class (" + i.reference + "), which a baseline file does not " +
                            "replace: accept it with cavity baselines approve --from " + from + " --why ...");
        CAVITY_TRY(judgedPixels(i.newExact, i.digest, from));
        const fs::path target = fs::path("images") / r.key / (i.image + fs::path(i.newExact).extension().string());
        writes.push_back({i.newExact, target});
        std::ostringstream line;
        line << "updated " << (fs::path(root) / target).string() << "  (from " << r.id;
        if (i.metrics)
            line << ": max abs " << i.metrics->maxAbs << ", RMSE " << i.metrics->rmse << ", SSIM " << i.metrics->ssim;
        else
            line << ": new baseline";
        said.push_back(line.str() + ")");
    }
    return {};
}

// Whether two configurations of one key rendered the same images.
bool sameImages(const gate::ConfigResult& a, const gate::ConfigResult& b) {
    if (a.images.size() != b.images.size()) return false;
    for (size_t i = 0; i < a.images.size(); ++i)
        if (a.images[i].image != b.images[i].image || a.images[i].digest != b.images[i].digest) return false;
    return true;
}

int updateCommand(const std::vector<std::string>& argv) {
    std::string from = "out/gate", filterText, root;
    auto parsed = parseFlags(updateSpec(), std::vector<std::string>(argv.begin() + 1, argv.end()));
    if (!parsed) return fail("cavity baselines update", parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    const ParsedFlags& p = *parsed;
    for (const auto& [flag, v] : p.values) {
        if (flag == "--from") from = v;
        else if (flag == "--filter") filterText = v;
        else if (flag == "--baselines") root = v;
    }
    if (root.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail("cavity baselines update", found.error());
        root = *found;
    }
    std::optional<std::regex> filter;
    if (!filterText.empty()) {
        auto r = parseFilter("--filter", filterText);
        if (!r) return fail("cavity baselines update", r.error());
        filter = std::move(*r);
    }
    if (auto st = gate::recoverBaselineUpdate(root); !st) return fail("cavity baselines update", st.error());
    auto run = loadGateJson(from);
    if (!run) return fail("cavity baselines update", run.error());
    auto sources = kernelSourceCopies(*run, root, from, p.has("--with-kernel-source"));
    if (!sources) return fail("cavity baselines update", sources.error());
    // One baseline key is shared by every API and stage: take the first
    // selected configuration of each key.
    std::map<std::string, const gate::ConfigResult*> taken;   // key -> the configuration it took
    std::vector<std::string> apart;   // configurations whose images differ from the one taken for their key
    std::vector<gate::BaselineWrite> writes;
    std::vector<std::string> said;
    const bool takeChanged = !sources->empty();
    for (const auto& r : run->results) {
        if (!selectedForUpdate(r, filter, takeChanged) || !r.error.empty()) continue;
        if (const auto [at, first] = taken.emplace(r.key, &r); !first) {
            if (!sameImages(r, *at->second)) apart.push_back(r.id + " (the baseline takes " + at->second->id + "'s)");
            continue;
        }
        if (auto st = addWrites(r, filter.has_value(), takeChanged, from, root, writes, said); !st)
            return fail("cavity baselines update", st.error());
    }
    if (filter && std::none_of(run->results.begin(), run->results.end(),
                               [&](const gate::ConfigResult& r) { return std::regex_search(r.id, *filter); }))
        return fail("cavity baselines update", badInput("--filter " + filterText + ": matches no configuration of " + from +
                                                        " (nothing updated, the baselines left as they were)"));
    if (auto st = onlyErrored(*run, filter, filterText, from, writes.empty()); !st) return fail("cavity baselines update", st.error());
    // All or nothing (harness/gate/baseline_update.h).
    if (auto st = gate::applyBaselineUpdate(root, writes); !st) return fail("cavity baselines update", st.error());
    for (const auto& line : said) std::cout << line << "\n";
    if (auto st = copyKernelSources(*sources, *run); !st) return fail("cavity baselines update", st.error());
    const size_t changed = writes.size();
    std::cout << changed << " baseline files updated\n";
    // Images of one key that differ between APIs or stages are judged against
    // the one taken by tolerance; past it, updating again only flips the file
    // between them. Approvals are per API and stage.
    if (!apart.empty())
        std::cout << "note: " << apart.size() << " selected configuration" << (apart.size() == 1 ? "" : "s")
                  << " rendered other images than the one their shared baseline took, e.g. " << apart[0]
                  << ": if the next gate fails them, accept each API's and stage's images by digest with `cavity "
                     "baselines approve --from "
                  << from << " --why ...` instead\n";
    if (const std::string hint = budgetOnlyHint(*run, filter.has_value(), from, root); !hint.empty()) std::cout << hint << "\n";
    return 0;
}

}  // namespace

}  // namespace cavity::cli
