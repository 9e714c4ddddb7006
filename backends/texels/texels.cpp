// Half floats through Imath's own conversion functions (the ones Imath::half's
// constructor and operator float call), used directly: with
// IMATH_HALF_NO_LOOKUP_TABLE they are header-only static inline functions,
// so the binaries that travel to the GPU machine (cavity_bench,
// cavity_render) need no libImath at run time, and no TU here shares an
// inline function with OpenImageIO's use of Imath::half.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include "texels.h"

#include <Imath/half.h>

#include <cmath>

namespace cavity::gpu::texels {

uint16_t toHalf(float value) { return imath_float_to_half(value); }

float fromHalf(uint16_t bits) { return imath_half_to_float(bits); }

float roundToHalf(float value) { return fromHalf(toHalf(value)); }

uint8_t toUnorm8(float value) {
    const float clamped = value > 0 ? std::fmin(value, 1.0f) : 0.0f;   // NaN -> 0, as GPUs do
    return uint8_t(std::floor(clamped * 255.0f + 0.5f));
}

float fromUnorm8(uint8_t value) { return float(value) / 255.0f; }

float roundToUnorm8(float value) { return fromUnorm8(toUnorm8(value)); }

}  // namespace cavity::gpu::texels
