// Texel conversions between the host's floats and the stored formats, in one
// place below both backends: what the Vulkan and GL backends pack for an
// upload and unpack after a readback, and what the CPU references round their
// results to (harness/kernel_runner.cpp's quantize) so that they see the
// precision a GPU image stores.
#pragma once

#include <cstdint>

namespace cavity::gpu::texels {

// IEEE binary16 through Imath (imath_float_to_half: round to nearest even;
// overflow to infinity; NaN stays NaN).
uint16_t toHalf(float value);
float fromHalf(uint16_t bits);
// The nearest half, as a float: what an R16F/RGBA16F image holds.
float roundToHalf(float value);

// UNORM8 as GPUs store it: clamped to [0, 1] (NaN to 0), times 255, rounded
// half up (Vulkan spec "Conversion from Floating-Point to Normalized Fixed-Point").
uint8_t toUnorm8(float value);
float fromUnorm8(uint8_t value);
// The nearest UNORM8 value, as a float: what an R8/RGBA8 image holds.
float roundToUnorm8(float value);

}  // namespace cavity::gpu::texels
