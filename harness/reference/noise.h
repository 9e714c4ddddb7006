// The CPU side of kernels/include/noise.glsl: per-pixel hashes and
// interleaved gradient noise, bit for bit (see there for why each is so).
#pragma once

#include "reference/namespace.h"
#include <cmath>
#include <cstdint>

namespace cavity::reference {

inline uint32_t pcgHash(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

inline float hashToUnit(uint32_t h) { return float(h >> 8u) * (1.0f / 16777216.0f); }

inline float pixelHash(int x, int y) { return hashToUnit(pcgHash(uint32_t(x) + uint32_t(y) * 65521u)); }

// phasePixel() with k interleaved layers per axis: the pixel itself, or its layer.
inline int phaseCoord(int v, int k) { return k > 1 ? v % k : v; }

// samplePhase(): the pixel's hash, or its layer's evenly spaced phase.
inline float samplePhase(int x, int y, int k) {
    if (k <= 1) return pixelHash(x, y);
    const int n = k * k;
    return float((y % k * k + x % k) * 7 % n) * (1.0f / float(n));
}

// IGN at a pixel centre (px, py) = (x + 0.5, y + 0.5).
inline float ign(float px, float py) {
    const float inner = 0.06711056f * px + 0.00583715f * py;
    const float outer = 52.982918f * (inner - std::floor(inner));
    return outer - std::floor(outer);
}

}  // namespace cavity::reference
