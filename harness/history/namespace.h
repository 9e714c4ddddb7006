// history/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::history without qualification.
// compare/ and gate/ are named where used: their readers of the run files.
#pragma once

namespace cavity::core {}
namespace cavity::stats {}

namespace cavity::history {
using namespace cavity::core;
using namespace cavity::stats;
}  // namespace cavity::history
