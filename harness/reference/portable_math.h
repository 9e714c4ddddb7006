// The CPU side of kernels/include/common.glsl's bit-exact helpers: the same
// operations in the same order, in float. This file must be compiled
// without fused multiply-add (CMakeLists.txt sets -ffp-contract=off), as the
// GLSL declares the matching values `precise`.
#pragma once

#include "reference/namespace.h"
#include <bit>
#include <cmath>
#include <cstdint>

#include "reference/vec.h"

namespace cavity::reference {

constexpr float kPi = 3.14159265f;   // common.glsl's PI

inline float lengthSquared(Vec3 v) { return v.x * v.x + v.y * v.y + v.z * v.z; }

// (cos, sin) of 2 pi turns by quarter-turn reduction and Taylor series;
// see common.glsl for why not std::cos / std::sin.
inline Vec2 cosSinTurns(float turns) {
    const float t = turns - std::floor(turns);
    const float quarter = std::floor(t * 4.0f + 0.5f);
    const float r = t - quarter * 0.25f;
    const float x = r * 6.2831855f;
    const float x2 = x * x;
    const float s = x * (1.0f + x2 * (-0.16666667f + x2 * (0.008333334f + x2 * (-0.0001984127f + x2 * 2.7557319e-06f))));
    const float c = 1.0f + x2 * (-0.5f + x2 * (0.041666668f + x2 * (-0.0013888889f + x2 * 2.4801588e-05f)));
    switch (int(quarter) & 3) {
    case 0: return {c, s};
    case 1: return {-s, c};
    case 2: return {-c, -s};
    default: return {s, -c};
    }
}

// 1 / x for x != 0 by an exponent-bit estimate and three Newton steps, the
// same bits as the GLSL (a division may differ by an ulp between the two).
// The subtraction is unsigned: GLSL's int arithmetic wraps, C++'s signed
// overflow is undefined (UBSan caught it for a negative x, which the
// half-resolution depth passes: the wrapped estimate carries the sign, and
// the Newton steps converge to 1 / x as for a positive x).
inline float portableReciprocal(float x) {
    float y = std::bit_cast<float>(uint32_t(0x7EF311C7u) - std::bit_cast<uint32_t>(x));
    for (int i = 0; i < 3; ++i) y = y * (2.0f - x * y);
    return y;
}

}  // namespace cavity::reference
