// The few GLSL vector operations the references need, in float, with
// GLSL's names, so that a reference reads like the kernel it mirrors.
#pragma once

#include "reference/namespace.h"
#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace cavity::reference {

struct Vec2 {
    float x = 0, y = 0;
};

struct Vec3 {
    float x = 0, y = 0, z = 0;
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }

inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a * (1.0f / length(a)); }
inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 abs(Vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline Vec3 max(Vec3 a, float b) { return {std::max(a.x, b), std::max(a.y, b), std::max(a.z, b)}; }
inline Vec3 mix(Vec3 a, Vec3 b, float t) { return a * (1.0f - t) + b * t; }

inline float fract(float x) { return x - std::floor(x); }
inline float clamp(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }

}  // namespace cavity::reference
