// reference/ uses core/ (the image type); its names are visible inside
// cavity::reference without qualification.
#pragma once

namespace cavity::core {}

namespace cavity::reference {
using namespace cavity::core;
}  // namespace cavity::reference
