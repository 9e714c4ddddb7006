// What the cavity commands that read a gate's output share (gate_command.cpp,
// approve_command.cpp); only the cavity binary links them.
#pragma once

#include "cli.h"
#include "gate/gate.h"

namespace cavity::cli {

// A gate output folder's gate.json; a missing one says to run the gate first.
Result<gate::GateRun> loadGateJson(const std::string& dir);

// --baselines's help, as every command that reads the baselines words it.
inline const std::string kBaselinesHelp =
    "folder with matrices.json, manifest.json, budgets.json, images/ (default: baselines/ of the checkout found "
    "from the working directory up, else of the source tree this binary was built from)";

}  // namespace cavity::cli
