// images/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::images without qualification.
#pragma once

namespace cavity::core {}

namespace cavity::images {
using namespace cavity::core;
}  // namespace cavity::images
