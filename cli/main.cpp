// The cavity command. Exit codes (README.md, "Exit codes"): 0 success,
// 1 a regression (gate), 2 bad usage or input, 3 a backend could not start,
// 4 an internal GPU error, 5 the image store cannot be reached, 6 a store
// object does not match its digest. `cavity history` uses 5 for a database
// server that cannot be reached or refuses the connection.
#include "cli.h"
#include "package/package.h"
#include "version.h"

#include <iostream>

namespace {

constexpr const char* kUsage =
    "usage: cavity <command> [flags]\n"
    "commands:\n"
    "  run        run kernel configurations, write images, results.json and a timing table\n"
    "  gate       run a matrix against baselines and budgets; junit.xml, summary.md, index.html\n"
    "  gate judge judge render folders written by cavity_render (the gate in two steps)\n"
    "  gate merge join shard outputs into one verdict\n"
    "  baselines update   accept new images as baselines\n"
    "  baselines approve  approve (or mark known bad) a run's image digests for their device class\n"
    "  baselines migrate-digests  rewrite approvals' FNV-1a digests as SHA-256\n"
    "  store check        fetch every approved image from the image store and check its digest\n"
    "  ab         two builds measured interleaved on one GPU, then compared pass by pass\n"
    "  compare    two runs (results.json or cavity_bench JSON) pass by pass: change, interval, verdict\n"
    "  quality    each AO kernel's mean absolute error against the ray-traced ground truth\n"
    "  history    runs kept in a database over commits: ingest, show, chart, alerts (change points)\n"
    "  kernels    the kernels: list, show NAME, check DIR (a kernel package on both APIs and stages)\n"
    "--kernels DIR (any command, repeatable) loads the kernel packages in DIR, as CAVITY_KERNELS does\n"
    "(folders separated by ':'); a package's kernel then works as a built-in one.\n"
    "`cavity COMMAND --help` lists a command's flags. `cavity` alone prints this and exits 2;\n"
    "`cavity --help` prints it and exits 0. `cavity --version` (cavity_render and cavity_bench too)\n"
    "prints the git commit and the build type it was built from.\n"
    "\n"
    "Examples:\n"
    "  cavity run --kernel alchemy_fast --backend gl,vk --res 1920x1080\n"
    "  cavity gate --filter '/alchemy/'\n"
    "  cavity compare main/results.json pr/results.json\n";

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    // Kernel packages first (--kernels DIR, anywhere on the line, and
    // CAVITY_KERNELS): every command then sees their kernels and parameters
    // as the built-ins'.
    if (const auto loaded = cavity::kernels::loadPackagesFromCommandLine(args); !loaded) {
        std::cerr << "cavity: " << cavity::flags::printable(loaded.error().message) << "\n";
        return 2;
    }
    if (!args.empty() && args[0] == "--version") {
        std::cout << cavity::flags::versionLine("cavity") << "\n";
        return 0;
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        std::cout << kUsage;
        return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    if (command == "run") return cavity::cli::runCommand(args);
    if (command == "gate") return cavity::cli::gateCommand(args);
    if (command == "baselines") return cavity::cli::baselinesCommand(args);
    if (command == "compare") return cavity::cli::compareCommand(args);
    if (command == "store") return cavity::cli::storeCommand(args);
    if (command == "ab") return cavity::cli::abCommand(args);
    if (command == "quality") return cavity::cli::qualityCommand(args);
    if (command == "history") return cavity::cli::historyCommand(args);
    if (command == "kernels") return cavity::cli::kernelsCommand(args);
    // One line, as every usage error (README "Exit codes").
    const std::string near = cavity::cli::nearest(command, {"run", "gate", "baselines", "compare", "quality", "store", "ab", "history", "kernels"});
    std::cerr << "cavity: unknown command '" << command << "'" << (near.empty() ? "" : " (did you mean " + near + "?)")
              << "; see cavity --help\n";
    return 2;
}
