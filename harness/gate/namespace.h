// gate/ uses these folders below it (tests/layering.py keeps them below);
// their names are visible inside cavity::gate without qualification.
#pragma once

namespace cavity::core {}
namespace cavity::stats {}
namespace cavity::pipeline {}
namespace cavity::images {}
namespace cavity::plan {}
namespace cavity::measure {}
namespace cavity::render {}
namespace cavity::store {}

namespace cavity::gate {
using namespace cavity::core;
using namespace cavity::stats;
using namespace cavity::pipeline;
using namespace cavity::images;
using namespace cavity::plan;
using namespace cavity::measure;
using namespace cavity::render;
using namespace cavity::store;
}  // namespace cavity::gate
