// An imported G-buffer: a capture from the user's own engine, read with
// OpenImageIO from ONE multi-channel OpenEXR file (subimage 0, any pixel
// type), turned into the images the ray-marched G-buffer pass would have
// written (kernels/passes/gbuffer_sdf/gbuffer_sdf.glsl), so every later pass reads it alike.
//
// The camera is the harness's (harness/core/camera.h): view space right-handed,
// looking down -Z, fovY 60 degrees, near 0.05, far 100, aspect = width /
// height of the image; image row 0 (the top of the EXR's display window) is
// the top of the view.
//
// Channels (names are case-sensitive; others are ignored):
//   P.X, P.Y, P.Z      view-space position. Used when present (all three).
//   Z                  otherwise: linear view depth, positive along -Z. x and y
//                      are rebuilt through the pixel centre with the harness
//                      projection (kernels/include/common.glsl viewRayAt):
//                        ndc = ((x, y) + 0.5) / (width, height) * 2 - 1
//                        P   = (ndc.x tan(fovY/2) aspect, -ndc.y tan(fovY/2), -1) * depth
//   N.X, N.Y, N.Z      view-space normal (required). Used as is when within
//                      1e-3 of unit length (half-float storage), else renormalised.
//   albedo.R, albedo.G, albedo.B
//                      linear albedo, optional (all three or none; default
//                      0.7 grey); clamped to [0, 1].
//
// Background: a pixel whose depth (-P.Z, or Z) is <= 0, i.e. P.Z >= 0 or
// Z <= 0, is background: position, normal and albedo all zero there, as the
// ray march leaves a miss. Every other pixel is a surface and its depth must
// lie in [near, far] = [0.05, 100], its normal must be nonzero.
//
// Errors (ErrorCode::BadInput, one line naming the file, the channel and
// pixel when one is at fault, the value and what is allowed): missing or
// unreadable file, not an OpenEXR file, deep data, a data window other than
// the display window, missing channels (the message lists the file's),
// a size other than the requested one ("wrong size"), any non-finite value
// in a channel read (background pixels included), a depth outside [near,
// far], a zero normal at a surface pixel.
#pragma once

#include "images/namespace.h"
#include "core/config.h"
#include "result.h"

#include <string>

namespace cavity::images {

// Albedo where the capture has no albedo.* channels.
constexpr float kImportDefaultAlbedo = 0.7f;

// Reads a capture. width and height: the size the run needs; 0 and 0 take
// the file's size. The message of every error starts with
// "--gbuffer-file <path>: ".
Result<GBufferImages> importGBuffer(const std::string& path, int width = 0, int height = 0);

}  // namespace cavity::images