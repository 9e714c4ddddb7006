// The tests use every harness folder: `using namespace cavity::harness;`
// makes the folders' names visible in a test without qualification. The
// product's folders name what they use instead (namespace.h, imports.h).
#pragma once

namespace cavity::core {}
namespace cavity::stats {}
namespace cavity::pipeline {}
namespace cavity::images {}
namespace cavity::plan {}
namespace cavity::measure {}
namespace cavity::render {}
namespace cavity::gate {}
namespace cavity::compare {}
namespace cavity::report {}

namespace cavity::harness {
using namespace cavity::core;
using namespace cavity::stats;
using namespace cavity::pipeline;
using namespace cavity::images;
using namespace cavity::plan;
using namespace cavity::measure;
using namespace cavity::render;
using namespace cavity::gate;
using namespace cavity::compare;
using namespace cavity::report;
}  // namespace cavity::harness
