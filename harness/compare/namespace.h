// compare/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::compare without qualification.
#pragma once

namespace cavity::core {}
namespace cavity::stats {}
namespace cavity::measure {}

namespace cavity::compare {
using namespace cavity::core;
using namespace cavity::stats;
using namespace cavity::measure;
}  // namespace cavity::compare
