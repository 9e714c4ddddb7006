// plan/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::plan without qualification.
#pragma once

namespace cavity::core {}
namespace cavity::pipeline {}

namespace cavity::plan {
using namespace cavity::core;
using namespace cavity::pipeline;
}  // namespace cavity::plan
