// What images/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::images without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/camera.h"
#include "core/config.h"
#include "core/image.h"
#include "core/progress.h"

namespace cavity::images {
using core::frameUniforms;
using core::GBufferImages;
using core::HostImage;
using core::kFar;
using core::kMaxResolution;
using core::kNear;
using core::stderrLock;
}  // namespace cavity::images
