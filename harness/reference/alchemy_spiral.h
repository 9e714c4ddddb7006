// The CPU twin of kernels/include/alchemy_spiral.glsl: Alchemy's sample
// spiral (McGuire et al., HPG 2011), the same operations in the same order,
// shared by ref_alchemy.cpp and ref_fast.cpp.
#pragma once

#include "reference/namespace.h"
#include "reference/portable_math.h"
#include "reference/reference.h"

#include <cmath>

namespace cavity::reference {

// The disc radius of sample i in pixels is (i + 0.5) * this.
inline float spiralDiscScale(const kernels::FrameUniforms& f, float R, int n, float d) {
    const float focal = 0.5f * float(f.size[1]) * portableReciprocal(f.camera[1]);
    return R * focal * portableReciprocal(float(n) * d);
}

struct SpiralSample {
    int x, y;   // the sample's pixel
    float h;    // its distance from the pixel centre, in pixels
};

// Sample i around pixel (x, y) with phase u (pixelHash).
inline SpiralSample spiralSample(int i, float u, float discScale, int x, int y) {
    const float turns = (float(i) + 0.5f) * 0.7777778f + u;
    const Vec2 dir = cosSinTurns(turns);
    const float h = (float(i) + 0.5f) * discScale;
    return {int(std::floor(float(x) + 0.5f + dir.x * h)), int(std::floor(float(y) + 0.5f + dir.y * h)), h};
}

}  // namespace cavity::reference
