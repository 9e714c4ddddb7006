// The gate's coverage by construction: every code path a kernel package
// declares, and whether some configuration of the stored matrices compiles
// and judges it. A defect planted in a path that no matrix reaches changes
// no image the gate looks at, so such a path is a hole in the gate, found
// here from the declarations rather than by a defect that slipped through.
#pragma once

#include "plan/matrix.h"
#include "kernel.h"

#include <map>
#include <string>
#include <vector>

namespace cavity::plan {

struct CodePath {
    std::string kernel;   // the package: "hemisphere_fast", "blur_separable_x"
    std::string path;     // "fragment", "exact=1", "scene=slats", a [[paths]] name
    std::string why;      // where it comes from: "stage", "bool parameter", the condition's text
    std::string text() const { return kernel + ":" + path; }
};

// What a kernel runs that a configuration picks:
//   - each stage it can run on (compute; fragment unless it writes a mip
//     chain, which always runs as compute);
//   - each value of each bool or enum parameter it reads (an option that
//     switches a branch, an include or a pass);
//   - each of its package's [[paths]].
// Kernels of the reference role (the ground truth) are never gated: none.
// Stages and options no valid configuration can reach are left out.
std::vector<CodePath> declaredPaths(const kernels::KernelDecl& k);

// The paths of one configuration: those of every pass of its pipeline, with
// the pass's stage, output size and parameter values.
std::vector<CodePath> pathsOf(const RunConfig& c);

// Each path some configuration of `matrices` reaches (CodePath::text), with
// the id of the first configuration that does, in matrix order.
std::map<std::string, std::string> reachedBy(const std::vector<Matrix>& matrices);

// Every declared path of every kernel that no configuration of `matrices`
// reaches, in kernel then declaration order.
std::vector<CodePath> uncovered(const std::vector<Matrix>& matrices);

}  // namespace cavity::plan
