// What reference/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::reference without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/image.h"

namespace cavity::reference {
using core::HostImage;
}  // namespace cavity::reference
