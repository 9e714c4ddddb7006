// render/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::render without qualification.
#pragma once

namespace cavity::core {}
namespace cavity::pipeline {}
namespace cavity::plan {}
namespace cavity::measure {}

namespace cavity::render {
using namespace cavity::core;
using namespace cavity::pipeline;
using namespace cavity::plan;
using namespace cavity::measure;
}  // namespace cavity::render
