// Runs one of our binaries as a user would, through the shell, and captures
// what it printed: the one helper the command-line tests share.
#pragma once

#include "harness_names.h"
#include <string>

namespace cavity::test {

using namespace cavity::harness;

struct Outcome {
    int code = -1;        // the exit status; -1 when killed by a signal or not started
    std::string output;   // what `redirect` sent into the pipe (by default stdout and stderr)
};

// `binary args redirect`, with `env` before it: VAR=value assignments, or
// `env -C DIR` to run the binary from DIR. `redirect` is
// how the shell sends the two streams into the pipe read here: "2>&1" for
// both, "2>/dev/null" for stdout only, "2>&1 >/dev/null" for stderr only.
Outcome runBinary(const std::string& binary, const std::string& args, const std::string& env = "",
                  const std::string& redirect = "2>&1");

// Removes the CPU renderers' approvals (device class llvmpipe) from the
// approvals.json of a copied baselines folder: a test about how the
// tolerance route judges an image, or about the baseline files, needs its
// images to take that route, which an approved digest would skip.
void dropCpuApprovals(const std::string& baselines);

}  // namespace cavity::test
