// pipeline/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::pipeline without qualification.
#pragma once

namespace cavity::core {}

namespace cavity::pipeline {
using namespace cavity::core;
}  // namespace cavity::pipeline
