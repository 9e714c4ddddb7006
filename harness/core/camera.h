// The projection every pass sees (FrameUniforms): a perspective camera with
// fovY 60 degrees, matching the backend contract (NDC y = -1 is image row 0,
// the top; depth in [0, 1]).
#pragma once

#include "kernel.h"

namespace cavity::core {

constexpr float kFovYDegrees = 60.0f;
constexpr float kNear = 0.05f;
constexpr float kFar = 100.0f;

// size: this pass's output; srcSize: the size its inputs were rendered at.
kernels::FrameUniforms frameUniforms(int width, int height, int srcWidth, int srcHeight);

}  // namespace cavity::core