// Reading one kernel.toml into a KernelDecl (package/declaration.cpp). Every
// error is one line: "FILE:LINE: KEY = VALUE: what is allowed".
#pragma once

#include "kernel.h"
#include "package/package.h"
#include "result.h"

#include <functional>
#include <string>

namespace cavity::kernels {

struct DeclarationInput {
    std::string text;          // kernel.toml's bytes
    std::string label;         // its path, as messages name it
    std::string keyPrefix;     // its folder's source keys start with this ("ao/gtao/", "mine/")
    // Whether the package holds a file of this path relative to its folder.
    std::function<bool(const std::string&)> hasFile;
    // Whether a kernel of this name is registered already (a built-in or a package loaded before).
    std::function<bool(const std::string&)> nameTaken;
    // One of the harness's own packages (kernels/ao/, kernels/passes/): it
    // may declare a pass of the pipeline, not only an AO estimator.
    bool builtIn = false;
    // Whether the cost formulas are tried over the parameters' ranges. The
    // harness's own packages skip it at every start (a large part of a start
    // under the sanitizers, study 2026-12-07_cpu_ci_time); a test tries them
    // once instead.
    bool checkCounts = true;
};

// The declaration, with the parameters it adds declared (ParamDecl) only
// when the whole file is good. `info` gets the name and the added params.
Result<KernelDecl> readDeclaration(const DeclarationInput& in, PackageInfo& info);

}  // namespace cavity::kernels
