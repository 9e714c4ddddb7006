// Kernels as packages: a folder holding a declaration (kernel.toml) and its
// GLSL, loaded at run time and registered beside the built-in kernels, so
// that every program sees a package kernel exactly as a built-in one
// (docs/kernels.md, "Your own kernel"; the format: docs/packages.md).
//
// Built-in packages live under kernels/ao/<name>/ (the AO estimators) and
// kernels/passes/<name>/ (the passes around them), and are embedded in the
// binary with the other kernel sources; a user's are found through
// --kernels DIR (any program, repeatable) and CAVITY_KERNELS (folders
// separated by ':'). DIR is a package folder or a folder of package folders.
#pragma once

#include "kernel.h"
#include "result.h"

#include <string>
#include <vector>

namespace cavity::kernels {

struct PackageInfo {
    std::string name;        // the kernel's
    std::string folder;      // on disk, or "kernels/ao/<name>" for a built-in package
    std::string declaration; // its kernel.toml, as messages name it
    bool builtIn = false;
    std::vector<std::string> sourceKeys;   // its files' keys (--kernel-source NAME)
    std::vector<std::string> addedParams;  // parameters it declares that the harness had not: flags it adds
};

// The packages loaded so far, built-in ones first.
const std::vector<PackageInfo>& packages();
const PackageInfo* findPackage(const std::string& kernel);

// Loads the package folders under `dir` (a package folder, or a folder of
// them, in name order). Every error is BadInput, one line that names the
// file and line, the key, the value and what is allowed; nothing is
// registered unless the whole folder loads.
Status loadPackages(const std::string& dir);

// Every program's first step: takes each `--kernels DIR` (or --kernels=DIR)
// out of `args` and loads it, after the folders of CAVITY_KERNELS. The
// error names the flag or the variable.
Status loadPackagesFromCommandLine(std::vector<std::string>& args);
// The same for a C main's argv (cavity_bench hands the rest to Google
// Benchmark): removes the flags from argv and lowers argc.
Status loadPackagesFromCommandLine(int& argc, char** argv);

// A source file a package brought: its text and the label its diagnostics
// use (the file's path). Null for any other name.
struct PackageSource {
    std::string text;
    std::string label;
};
const PackageSource* packageSource(const std::string& key);
// The key of a loaded package's GLSL file given by its path on disk (as its
// diagnostics label it), or "" for any other path.
std::string packageKeyOfFile(const std::string& path);

// Called by the registry once, after the C++ declarations: the embedded
// built-in packages (kernels/ao/*/kernel.toml, kernels/passes/*/kernel.toml). A broken one is a build
// mistake, thrown as std::logic_error.
void appendBuiltInPackages(std::vector<KernelDecl>& registry);
// True on the thread building the registry, while the built-in packages
// declare their parameters (params.cpp): paramDecls() then does not wait
// for the registry it is part of.
bool& registryBuilding();

}  // namespace cavity::kernels
