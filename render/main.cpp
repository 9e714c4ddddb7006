// cavity_render: the rendering half of the gate, and `quality`, for the GPU
// machine. It links no OpenImageIO (tests/test_render.cpp reads its dynamic
// section to keep it so); images go to a render folder that `cavity gate
// judge` reads. Exit codes as cavity's (README.md, "Exit codes").
#include "package/package.h"
#include "quality_command.h"
#include "values.h"
#include "version.h"
#include "render_command.h"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    // Kernel packages first (--kernels DIR, CAVITY_KERNELS): their kernels
    // and parameters are then flags and names like the built-ins'.
    if (const auto loaded = cavity::kernels::loadPackagesFromCommandLine(args); !loaded) {
        std::cerr << "cavity_render: " << loaded.error().message << "\n";
        return 2;
    }
    if (!args.empty() && args[0] == "--version") {
        std::cout << cavity::flags::versionLine("cavity_render") << "\n";
        return 0;
    }
    if (!args.empty() && args[0] == "quality")
        return cavity::flags::qualityCommand({args.begin() + 1, args.end()}, "cavity_render quality");
    return cavity::render::renderCommand(args);
}
