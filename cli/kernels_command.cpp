// `cavity kernels list|show NAME|check DIR`: the kernels the harness knows,
// built-in and loaded from packages (--kernels DIR, CAVITY_KERNELS), one
// kernel's declaration, and a package checked before it is used: its shader
// compiled on both APIs and both stages, and its declaration held to what
// the compiled shader reads (docs/packages.md).
#include "cli.h"
#include "compiler.h"
#include "core/text_table.h"
#include "package/package.h"
#include "params.h"
#include "pipeline/pipeline.h"
#include "reference/reference.h"

#include <filesystem>
#include <iostream>
#include <set>
#include <algorithm>

namespace cavity::cli {

namespace {

const CommandSpec& spec(const std::string& sub) {
    static const CommandSpec list{
        "cavity kernels list",
        "Every kernel the harness knows: its role, the package folder it comes from, whether it has a CPU reference, its "
        "summary. --markdown prints the AO kernels as the tables README.md and docs/kernels.md hold (a test keeps them "
        "equal).",
        {{"--markdown", "TABLE",
          "the AO kernels as a Markdown table: kernels (name and summary, with its sources) or pipelines (its passes "
          "at full resolution, and its package)"}},
        "",
        "",
        "",
        {"cavity kernels list", "cavity --kernels my_kernels/ kernels list", "cavity kernels list --markdown pipelines"}};
    static const CommandSpec show{"cavity kernels show", "One kernel's declaration: parameters with their defaults and "
                                  "ranges, inputs, outputs, its cost per pixel at the defaults, its passes, its files.",
                                  {}, "NAME", "a kernel's name (cavity kernels list)", "", {"cavity kernels show gtao"}};
    static const CommandSpec check{
        "cavity kernels check",
        "Loads the kernel package(s) in DIR, compiles each on Vulkan and OpenGL, compute and fragment, and holds its "
        "declaration to the compiled shader: every declared parameter, array and input must be read. Prints the "
        "flags it adds and what it lacks.",
        {},
        "DIR",
        "a kernel package folder, or a folder of them",
        "\nExit codes: 0 every package passed, 2 a declaration or shader error (one line each).",
        {"cavity kernels check my_kernels/my_ao"}};
    return sub == "list" ? list : sub == "show" ? show : check;
}

std::string roleName(kernels::Role r) {
    switch (r) {
    case kernels::Role::Ao: return "ao";
    case kernels::Role::Reference: return "reference";
    case kernels::Role::GBuffer: return "gbuffer";
    case kernels::Role::Pyramid: return "pyramid";
    case kernels::Role::Downsample: return "downsample";
    case kernels::Role::Upsample: return "upsample";
    case kernels::Role::Blur: return "blur";
    case kernels::Role::Indirect: return "indirect";
    case kernels::Role::Composite: return "composite";
    }
    return "?";
}

std::string origin(const kernels::KernelDecl& k) {
    const auto* p = kernels::findPackage(k.name);
    return p ? p->folder : "built in (kernels/)";
}

// A Markdown cell: no '|' may end it early.
std::string cell(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '|') out += "\\|";
        else out += c;
    }
    return out;
}

// The AO kernels (and the reference) as Markdown, generated from their
// packages so that no hand-kept list can fall behind them.
int markdown(const std::string& table) {
    std::vector<const kernels::KernelDecl*> rows;
    for (const auto role : {kernels::Role::Ao, kernels::Role::Reference})
        for (const auto& k : kernels::all())
            if (k.role == role) rows.push_back(&k);
    if (table == "kernels") {
        std::cout << "| `--kernel` | what | after |\n| --- | --- | --- |\n";
        for (const auto* k : rows) {
            std::string after;
            for (const auto& source : k->sources) after += (after.empty() ? "" : "; ") + source;
            std::cout << "| `" << k->name << "` | " << cell(k->summary) << " | " << cell(after.empty() ? "ours" : after)
                      << " |\n";
        }
        return 0;
    }
    std::cout << "| `--kernel` | passes at full resolution | package | CPU reference |\n| --- | --- | --- | --- |\n";
    for (const auto* k : rows) {
        core::RunConfig c;
        c.kernel = k->name;
        std::string passes;
        for (const auto& p : pipeline::buildPasses(c)) passes += (passes.empty() ? "" : " → ") + p.kernel;
        std::cout << "| `" << k->name << "` | " << passes << " | `" << origin(*k) << "/` | "
                  << (reference::hasReference(k->name) ? "yes" : "no: gated by approvals") << " |\n";
    }
    return 0;
}

int list() {
    core::TextTable t({{"kernel"}, {"role"}, {"from"}, {"CPU reference"}, {"summary"}});
    for (const auto& k : kernels::all())
        t.add({k.name, roleName(k.role), origin(k), reference::hasReference(k.name) ? "yes" : "no", k.summary});
    t.print();
    return 0;
}

std::string paramLine(const kernels::KernelDecl& k, const kernels::KernelParam& p) {
    std::string s = "  --" + p.name() + " " + kernels::valueText(*p.decl, p.def) + "  (" + kernels::allowedValues(*p.decl) + ")";
    // Compiled in: each value is its own build of the shader.
    if (std::find(k.compileTime.begin(), k.compileTime.end(), p.name()) != k.compileTime.end()) s += " [compiled in]";
    // This kernel's note on it, else what the parameter is (its help).
    if (!p.note.empty()) s += ": " + p.note;
    else if (!p.decl->help.empty()) s += ": " + p.decl->help;
    return s;
}

int show(const std::string& name) {
    const auto* k = kernels::find(name);
    if (!k)
        return fail("cavity kernels show", badInput("'" + name + "': no such kernel (cavity kernels list; a package's "
                                                    "kernel is known once loaded: --kernels DIR or CAVITY_KERNELS)"));
    std::cout << k->name << " (" << roleName(k->role) << ", " << origin(*k) << "): " << k->summary << "\n";
    for (const auto& s : k->sources) std::cout << "source: " << s << "\n";
    std::cout << "file: " << kernels::sourceLabel(k->file) << "\nparameters (default, allowed):\n";
    for (const auto& p : k->params) std::cout << paramLine(*k, p) << "\n";
    std::cout << "inputs:";
    for (const auto& i : k->inputs) std::cout << " " << i.name;
    std::cout << "\noutputs:";
    for (const auto& o : k->outputs) std::cout << " " << o.name << " (" << gpu::formatName(o.format) << ")";
    std::cout << "\n";
    const auto values = kernels::withDefaults(*k);
    if (k->cost) {
        const auto c = k->cost(values, {true, k->workgroup});
        std::cout << "cost per pixel at the defaults: " << c.fetchesPerPixel << " fetches, " << c.bytesPerPixel
                  << " bytes, " << c.fetchSlotsPerPixel << " fetch slots, " << c.dramBytesPerPixel << " DRAM bytes\n";
    }
    if (k->role == kernels::Role::Ao) {
        core::RunConfig c;
        c.kernel = k->name;
        std::cout << "passes (full resolution):";
        for (const auto& p : pipeline::buildPasses(c)) std::cout << " " << p.kernel;
        std::cout << "\n";
    }
    std::cout << "CPU reference: " << (reference::hasReference(k->name) ? "yes" : "none") << "\n";
    return 0;
}

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

int check(const std::string& dir) {
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
    const auto endsWith = [&](const std::string& tail) {
        return given.size() > tail.size() && given.compare(given.size() - tail.size() - 1, std::string::npos, "/" + tail) == 0;
    };
    // The package of that folder, or each package inside a folder of them,
    // loaded already (CAVITY_KERNELS, --kernels) or loaded now.
    const auto choose = [&] {
        const fs::path root = fs::weakly_canonical(dir, ec);
        for (const auto& p : kernels::packages()) {
            std::error_code e2;
            const fs::path folder = fs::weakly_canonical(p.folder, e2);
            const auto rel = folder.lexically_relative(root);
            const bool inside = !e2 && !rel.empty() && *rel.begin() != "..";
            if ((!p.builtIn && inside) || (p.builtIn && (endsWith(p.folder) || fs::equivalent(p.folder, dir, e2))))
                chosen.push_back(p);
        }
    };
    choose();
    if (chosen.empty()) {
        if (const auto s = kernels::loadPackages(dir); !s) return fail("cavity kernels check", s.error());
        choose();
    }
    if (chosen.empty())
        return fail("cavity kernels check", badInput(dir + ": no kernel package in it (a folder holding kernel.toml, or a folder of them)"));
    int bad = 0;
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

}  // namespace

int kernelsCommand(const std::vector<std::string>& argv) {
    const std::vector<std::string> subs = {"list", "show", "check", "coverage"};
    if (!argv.empty() && (argv[0] == "--help" || argv[0] == "-h")) {
        std::cout << "Usage: cavity kernels list|show NAME|check DIR|coverage [OPTIONS]\n"
                     "  list         every kernel: role, package folder, CPU reference, summary\n"
                     "  show NAME    one kernel's declaration, cost and passes\n"
                     "  check DIR    a kernel package compiled on both APIs and stages, held to its shader\n"
                     "  coverage     every code path of every kernel reached by a stored gate matrix\n"
                     "`cavity kernels SUBCOMMAND --help` lists a subcommand's flags.\n";
        return 0;
    }
    if (!argv.empty() && argv[0] == "coverage") return coverageCommand({argv.begin() + 1, argv.end()});
    if (argv.empty() || (argv[0] != "list" && argv[0] != "show" && argv[0] != "check")) {
        const std::string near = argv.empty() ? "" : nearest(argv[0], subs);
        std::cerr << "cavity kernels: " << (argv.empty() ? "needs a subcommand" : "unknown subcommand '" + argv[0] + "'")
                  << " (list, show NAME, check DIR, coverage)" << (near.empty() ? "" : "; did you mean " + near + "?") << "\n";
        return 2;
    }
    const std::string program = "cavity kernels " + argv[0];
    auto parsed = parseFlags(spec(argv[0]), {argv.begin() + 1, argv.end()});
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    if (argv[0] == "list") {
        std::string table;
        for (const auto& [flag, value] : parsed->values)
            if (flag == "--markdown") table = value;
        if (!table.empty() && table != "kernels" && table != "pipelines")
            return fail(program, badInput("--markdown " + table + ": must be kernels or pipelines"));
        return table.empty() ? list() : markdown(table);
    }
    if (parsed->positionals.size() != 1) {
        std::string extra;
        for (size_t i = 1; i < parsed->positionals.size(); ++i) extra += " '" + parsed->positionals[i] + "'";
        return fail(program, badInput((argv[0] == "show" ? std::string("give one kernel's NAME") : "give one package folder DIR") +
                                      (extra.empty() ? "" : ", not also" + extra)));
    }
    return argv[0] == "show" ? show(parsed->positionals[0]) : check(parsed->positionals[0]);
}

}  // namespace cavity::cli
