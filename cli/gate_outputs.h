// What the cavity commands that read a gate's output share (gate_command.cpp,
// approve_command.cpp); only the cavity binary links them.
#pragma once

#include "cli.h"
#include "gate/gate.h"

namespace cavity::cli {

// A gate output folder's gate.json; a missing one says to run the gate first.
Result<gate::GateRun> loadGateJson(const std::string& dir);

}  // namespace cavity::cli
