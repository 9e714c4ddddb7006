// measure/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::measure without qualification.
#pragma once

namespace cavity::core {}
namespace cavity::stats {}
namespace cavity::pipeline {}
namespace cavity::images {}
namespace cavity::plan {}

namespace cavity::measure {
using namespace cavity::core;
using namespace cavity::stats;
using namespace cavity::pipeline;
using namespace cavity::images;
using namespace cavity::plan;
}  // namespace cavity::measure
