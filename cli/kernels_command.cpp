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
        "a kernel package folder, or a folder of them (the checkout's kernels/ao: the built-in ones)",
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
    return argv[0] == "show" ? show(parsed->positionals[0]) : kernelsCheck(parsed->positionals[0]);
}

}  // namespace cavity::cli
