// `cavity kernels check DIR`: a package compiled on both APIs and both
// stages before it is used, and its declaration held to what the compiled
// shader reads (docs/packages.md). DIR is a package, a folder of them, or
// the checkout's own kernels/ folders, whose packages are the built-in ones.
#include "cli.h"
#include "compiler.h"
#include "package/package.h"
#include "params.h"
#include "reference/reference.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>

namespace cavity::cli {

namespace {

// Whether the kernel's derived arrays (KernelDecl::derive, filled on the
// CPU: a kernel table, blur weights) change with the parameter: the shader
// then reads it through them.
bool derivedFrom(const kernels::KernelDecl& k, const kernels::KernelParam& p) {
    if (!k.derive) return false;
    const auto values = kernels::withDefaults(k);
    std::map<std::string, std::vector<float>> base, moved;
    k.derive(values, base);
    const auto& d = *p.decl;
    for (const double v : {p.def + 1, p.def - 1, d.min, d.max}) {
        if (v == p.def || !kernels::checkValue(d, v)) continue;
        auto changed = values;
        changed[p.name()] = v;
        moved.clear();
        k.derive(changed, moved);
        return moved != base;
    }
    return false;
}

// What the compiled shader reads, against what the declaration says it reads.
std::vector<std::string> disagreements(const kernels::KernelDecl& k, const std::vector<std::string>& active) {
    std::set<std::string> read;
    for (const auto& a : active) read.insert(a.substr(a.rfind('.') == std::string::npos ? 0 : a.rfind('.') + 1));
    const auto* pkg = kernels::findPackage(k.name);
    const std::string where = pkg ? pkg->declaration : k.name;
    std::vector<std::string> out;
    // A compiled-in value reaches the shader as CAVITY_CONST_<name> (also);
    // a switch the harness reads need not reach it at all.
    const auto compiled = [&](const std::string& n) {
        return std::find(k.compileTime.begin(), k.compileTime.end(), n) != k.compileTime.end();
    };
    for (const auto& p : k.params)
        if (!read.count(p.name()) && !read.count(p.name() + "[0]") && !compiled(p.name()) &&
            !kernels::readByHarness(p.name()) && !derivedFrom(k, p))
            out.push_back(where + ": params: '" + p.name() + "' is declared, but the shader never reads P." + p.name() +
                          " (the uniform block is made from the declaration: drop it, or read it)");
    for (const auto& a : k.arrays)
        if (!read.count(a.name) && !read.count(a.name + "[0]"))
            out.push_back(where + ": arrays: '" + a.name + "' is declared, but the shader never reads P." + a.name);
    for (const auto& i : k.inputs)
        if (!read.count("in_" + i.name))
            out.push_back(where + ": inputs: '" + i.name + "' is declared, but the shader never reads in_" + i.name);
    // The compute stage's output images (out_<name>, or out_<name>_<level>
    // of a mip chain): one that no write reaches would leave its image as
    // it was made, black, and every pass after it reading that.
    for (const auto& o : k.outputs)
        if (!read.count("out_" + o.name) && !read.count("out_" + o.name + "_0"))
            out.push_back(where + ": outputs: '" + o.name + "' is declared, but the shader never calls write_" + o.name);
    return out;
}

// A mip chain written by one dispatch runs on the compute stage only
// (pipeline::passStage), whatever --stage says.
bool computeOnly(const kernels::KernelDecl& k) {
    return std::any_of(k.outputs.begin(), k.outputs.end(), [](const auto& o) { return o.oneDispatch && o.mipLevels > 1; });
}

// A compiler's message (one line, its errors joined by " | "): glslang's
// first error, with a count of those after it, which follow from it (an
// undeclared field of P makes each expression that uses it an operand
// error printing the whole block type).
std::string firstCompileError(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    const std::string sep = " | ERROR: ";
    size_t more = 0;
    for (size_t at = message.find(sep); at != std::string::npos; at = message.find(sep, at + 1)) ++more;
    std::string out = message.substr(0, message.find(sep));
    if (out.find("no such field in structure 'P'") != std::string::npos)
        out += " (a parameter the shader reads is declared in kernel.toml's [[params]])";
    if (more) out += " (and " + std::to_string(more) + " more that follow from it)";
    return out;
}

std::vector<std::string> checkOne(const kernels::KernelDecl& k) {
    std::vector<std::string> problems;
    if (!k.reference.empty() && !reference::isReference(k.reference)) {
        std::string names;
        for (const auto& n : reference::referenceNames()) names += (names.empty() ? "" : ", ") + n;
        const auto* pkg = kernels::findPackage(k.name);
        problems.push_back((pkg ? pkg->declaration : k.name) + ": reference = " + k.reference +
                           ": no CPU reference of that name; the registered ones are " + names +
                           " (a package without one leaves the line out)");
    }
    const auto values = kernels::withDefaults(k);
    std::map<std::string, size_t> firstSeen;   // a compile error, without its API -> its problem
    std::map<size_t, std::string> alsoIn;      // problem -> the other APIs and stages it failed
    for (const auto api : {gpu::Api::Vulkan, gpu::Api::OpenGL}) {
        for (const auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
            if (stage == gpu::Stage::Fragment && computeOnly(k)) continue;
            auto src = kernels::assemble(k, stage, {}, &values);
            if (!src) {   // the same on every API: said once
                if (std::find(problems.begin(), problems.end(), src.error().message) == problems.end())
                    problems.push_back(src.error().message);
                continue;
            }
            auto active = kernels::activeUniforms(*src, api);
            if (!active) {
                // The message names the API; the stage tells its twin apart.
                // One error of the shared body fails every API and stage
                // alike: said once, with where else it failed.
                std::string message = firstCompileError(active.error().message);
                const std::string where = std::string(api == gpu::Api::Vulkan ? "vk" : "gl") + " " +
                                          (stage == gpu::Stage::Compute ? "compute" : "fragment");
                std::string same = message;
                for (const char* tag : {" (vk)", " (gl)"})
                    if (const auto at = same.find(tag); at != std::string::npos) same.erase(at, 5);
                if (const auto seen = firstSeen.find(same); seen != firstSeen.end()) {
                    alsoIn[seen->second] += ", " + where;
                    continue;
                }
                firstSeen[same] = problems.size();
                problems.push_back(where + ": " + message);
                continue;
            }
            if (api == gpu::Api::Vulkan && stage == gpu::Stage::Compute) {
                // An interleaved kernel reads its layers (zlayers) only when
                // it runs in more than one: what either build reads counts.
                if (k.interleaved) {
                    auto layered = values;
                    layered["interleave"] = 2;
                    if (auto src2 = kernels::assemble(k, stage, {}, &layered); src2)
                        if (auto more = kernels::activeUniforms(*src2, api); more)
                            active->insert(active->end(), more->begin(), more->end());
                }
                for (auto& d : disagreements(k, *active)) problems.push_back(std::move(d));
            }
        }
    }
    for (const auto& [i, where] : alsoIn) problems[i] += " (the same on " + where.substr(2) + ")";
    return problems;
}

// Whether `path` ends with the components of the relative path `tail`:
// "/src/cavity/kernels/ao" ends with "kernels/ao", not with "ls/ao".
bool endsWithPath(const std::string& path, const std::string& tail) {
    const std::string t = "/" + tail;
    return path.size() >= t.size() && path.compare(path.size() - t.size(), std::string::npos, t) == 0;
}

// The checkout's kernels/ folder holds the built-in packages on disk: a
// folder of them (kernels/, kernels/ao) names the built-in package
// kernels/ao/<name> when its package folder is there, below `given`.
bool holdsBuiltIn(const std::string& given, const std::string& folder) {
    namespace fs = std::filesystem;
    std::vector<std::string> parts;
    for (const auto& c : fs::path(folder)) parts.push_back(c.string());
    std::string head;
    for (size_t n = 1; n < parts.size(); ++n) {
        head += "/" + parts[n - 1];
        fs::path below = given;
        for (size_t i = n; i < parts.size(); ++i) below /= parts[i];
        std::error_code ec;
        if (endsWithPath(given, head.substr(1)) && fs::is_regular_file(below / "kernel.toml", ec))
            return true;
    }
    return false;
}

// Package folders below a folder of built-in packages that this build did
// not embed (added to kernels/ since it was built): each is said, not
// skipped, and counted as a failure.
int unembedded(const std::string& given, const std::vector<kernels::PackageInfo>& chosen) {
    namespace fs = std::filesystem;
    if (std::none_of(chosen.begin(), chosen.end(), [](const auto& p) { return p.builtIn; })) return 0;
    std::error_code ec;
    int bad = 0;
    for (auto it = fs::recursive_directory_iterator(given, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->path().filename() != "kernel.toml") continue;
        const std::string folder = it->path().parent_path().string();
        const bool known =
            std::any_of(chosen.begin(), chosen.end(), [&](const auto& p) { return endsWithPath(folder, p.folder); });
        if (known) continue;
        std::cerr << "cavity kernels check: " << folder
                  << ": a package among the built-in ones that this build has not embedded (rebuild, or keep it in a "
                     "folder of its own and load it with --kernels)\n";
        ++bad;
    }
    return bad;
}

}  // namespace

int kernelsCheck(const std::string& dir) {
    (void)kernels::all();   // the built-in packages load with the registry
    namespace fs = std::filesystem;
    std::vector<kernels::PackageInfo> chosen;
    // A package loaded already (a built-in one, or by --kernels) is checked as
    // loaded. A built-in one is named by its folder in the repository
    // (kernels/ao/<name>): from any working folder, a path that ends so is it.
    std::error_code ec;
    if (dir.empty()) return fail("cavity kernels check", badInput("DIR '': empty; give a package's folder"));
    std::string given = fs::absolute(dir, ec).lexically_normal().string();
    if (ec) return fail("cavity kernels check", badInput(dir + ": " + ec.message()));
    while (given.size() > 1 && given.back() == '/') given.pop_back();
    // The package of that folder, or each package inside a folder of them,
    // loaded already (CAVITY_KERNELS, --kernels) or loaded now.
    const auto choose = [&] {
        const fs::path root = fs::weakly_canonical(dir, ec);
        for (const auto& p : kernels::packages()) {
            std::error_code e2;
            const fs::path folder = fs::weakly_canonical(p.folder, e2);
            const auto rel = folder.lexically_relative(root);
            const bool inside = !e2 && !rel.empty() && *rel.begin() != "..";
            if ((!p.builtIn && inside) ||
                (p.builtIn && (endsWithPath(given, p.folder) || fs::equivalent(p.folder, dir, e2) || holdsBuiltIn(given, p.folder))))
                chosen.push_back(p);
        }
    };
    choose();
    int bad = unembedded(given, chosen);
    if (chosen.empty()) {
        if (const auto s = kernels::loadPackages(dir); !s) return fail("cavity kernels check", s.error());
        choose();
    }
    if (chosen.empty())
        return fail("cavity kernels check", badInput(dir + ": no kernel package in it (a folder holding kernel.toml, or a folder of them)"));
    for (const auto& info : chosen) {
        const auto* k = kernels::find(info.name);
        const auto problems = checkOne(*k);
        for (const auto& p : problems) std::cerr << "cavity kernels check: " << p << "\n";
        bad += problems.empty() ? 0 : 1;
        std::cout << info.name << " (" << info.declaration << "): "
                  << (problems.empty() ? std::string("compiles on vk and gl, ") +
                                             (computeOnly(*k) ? "compute (a one-dispatch mip chain)" : "compute and fragment") +
                                             "; the declaration matches the shader"
                                       : std::to_string(problems.size()) + " problem(s)")
                  << "\n";
        std::cout << "  flags it adds:";
        if (info.addedParams.empty()) std::cout << " none new (every parameter it reads was declared before it)";
        for (const auto& n : info.addedParams) {
            const auto* p = kernels::findParam(n);
            std::cout << " --" << n << " (" << kernels::allowedValues(*p) << ")";
        }
        std::cout << "\n  CPU reference: "
                  << (reference::hasReference(k->name)
                          ? "yes"
                          : "none: its images are gated by approved digests (cavity baselines approve), and its quality "
                            "is measured against the ground truth (cavity quality)")
                  << "\n";
    }
    return bad ? 2 : 0;
}

}  // namespace cavity::cli
