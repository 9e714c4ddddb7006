// stats/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::stats without qualification.
#pragma once

namespace cavity::core {}

namespace cavity::stats {
using namespace cavity::core;
}  // namespace cavity::stats
