// What store/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::store without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/digest.h"
#include "core/image.h"
#include "core/json_file.h"

namespace cavity::store {
using core::HostImage;
using core::imageDigest;
using core::writeFileAtomically;
}  // namespace cavity::store
