// store/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::store without qualification.
#pragma once

namespace cavity::core {}
namespace cavity::render {}

namespace cavity::store {
using namespace cavity::core;
using namespace cavity::render;
}  // namespace cavity::store
