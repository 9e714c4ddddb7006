// What pipeline/ uses from the folders below it, named one by one: a name here
// is visible inside cavity::pipeline without qualification. Every other name
// from below is written qualified (core::, measure::). The folders are those
// its CMake target links (tests/layering.py holds the includes to the links).
#pragma once

#include "core/camera.h"
#include "core/config.h"
#include "core/image.h"

namespace cavity::pipeline {
using core::frameUniforms;
using core::HostImage;
using core::importStem;
using core::kMaxResolution;
using core::RunConfig;
}  // namespace cavity::pipeline
