// `cavity kernels coverage`: every code path the kernel packages declare
// (harness/plan/coverage.h), checked against the configurations of the
// stored matrices. A path no matrix compiles and judges is a place where a
// defect changes no image the gate looks at.
#include "cli.h"
#include "gate_outputs.h"
#include "core/json_file.h"
#include "plan/coverage.h"

#include <filesystem>
#include <iostream>
#include <set>

namespace cavity::cli {

namespace fs = std::filesystem;

namespace {

const CommandSpec& coverageSpec() {
    static const CommandSpec spec{
        "cavity kernels coverage",
        "Checks that every code path of every kernel, built-in and loaded from packages, is compiled and judged by some "
        "configuration of the stored gate matrices: each stage a kernel can run on, each value of each bool or enum "
        "parameter it reads, and each path its package declares under [[paths]] (a remainder, a table size, the "
        "smallest levels). Prints the count, or one line listing every path no configuration reaches.",
        {{"--matrix", "NAMES", "the matrices to count (comma-separated; default: every matrix in matrices.json)"},
         {"--kernel", "NAMES", "only these kernels' paths (comma-separated; default: every kernel; your packages' in "
                               "a folder of baselines of your own)"},
         {"--baselines", "DIR", kBaselinesHelp},
         {"--list", "", "print every path, and the first configuration that reaches it (or \"not reached\")"}},
        "",
        "",
        "\nExit codes: 0 every path is reached, 1 some path is not (listed on one line), 2 bad input.",
        {"cavity kernels coverage", "cavity kernels coverage --matrix ci,gpu-cpu --list",
         "cavity --kernels my_kernels/ kernels coverage --kernel my_ao"}};
    return spec;
}

// --kernel's names, each a kernel that is loaded.
Result<std::set<std::string>> kernelNames(const std::string& flag, const std::string& value) {
    CAVITY_ASSIGN(const auto list, splitList(flag, value));
    std::set<std::string> out;
    for (const auto& k : list) {
        if (!kernels::find(k))
            return badInput(flag + " " + k + ": unknown kernel (a package's: load it with --kernels DIR or CAVITY_KERNELS)");
        out.insert(k);
    }
    return out;
}

}  // namespace

int coverageCommand(const std::vector<std::string>& argv) {
    const std::string program = "cavity kernels coverage";
    auto parsed = parseFlags(coverageSpec(), argv);
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    std::string root, names;
    std::set<std::string> only;   // --kernel: empty, every kernel
    for (const auto& [flag, value] : parsed->values) {
        if (flag == "--baselines") root = value;
        else if (flag == "--matrix") names = value;
        else if (flag == "--kernel") {
            auto list = kernelNames(flag, value);
            if (!list) return fail(program, list.error());
            only = std::move(*list);
        }
    }
    const auto counted = [&](const std::string& kernel) { return only.empty() || only.count(kernel) > 0; };
    if (root.empty()) {
        auto found = defaultBaselines();
        if (!found) return fail(program, found.error());
        root = *found;
    }
    const std::string path = (fs::path(root) / "matrices.json").string();
    std::vector<std::string> wanted;
    if (names.empty()) {
        auto doc = core::readJsonFile(path);
        if (!doc) return fail(program, doc.error());
        if (!doc->is_object()) return fail(program, badInput(path + ": must be an object of matrices by name"));
        for (const auto& [name, m] : doc->items()) wanted.push_back(name);
        if (wanted.empty()) return fail(program, badInput(path + ": holds no matrix (nothing to count coverage over)"));
    } else {
        auto list = splitList("--matrix", names);
        if (!list) return fail(program, list.error());
        wanted = std::move(*list);
    }
    std::vector<plan::Matrix> matrices;
    size_t configs = 0;
    std::string list;
    for (const auto& name : wanted) {
        auto m = plan::loadMatrix(path, name);
        if (!m) return fail(program, m.error());
        configs += m->expand().size();
        list += (list.empty() ? "" : ", ") + name;
        matrices.push_back(std::move(*m));
    }
    size_t declared = 0, kernelCount = 0;
    for (const auto& k : kernels::all())
        if (counted(k.name)) {
            declared += plan::declaredPaths(k).size();
            ++kernelCount;
        }
    auto missing = plan::uncovered(matrices);
    std::erase_if(missing, [&](const plan::CodePath& p) { return !counted(p.kernel); });
    if (parsed->has("--list")) {
        const auto reached = plan::reachedBy(matrices);
        for (const auto& k : kernels::all())
            for (const auto& p : plan::declaredPaths(k)) {
                if (!counted(k.name)) continue;
                const auto at = reached.find(p.text());
                std::cout << p.text() << "  " << (at == reached.end() ? "not reached" : at->second) << "\n";
            }
    }
    if (missing.empty()) {
        std::cout << program << ": all " << declared << " paths of " << kernelCount
                  << " kernels are compiled and judged by " << list << " (" << configs << " configurations)\n";
        return 0;
    }
    std::string line;
    for (const auto& p : missing)
        line += (line.empty() ? "" : ", ") + p.text() + (p.why == "stage" || p.why.find("parameter") != std::string::npos
                                                              ? ""
                                                              : " (" + p.why + ")");
    std::cerr << program << ": " << missing.size() << " of " << declared << " paths no configuration of " << list
              << " compiles and judges: " << line << "\n";
    return 1;
}

}  // namespace cavity::cli
