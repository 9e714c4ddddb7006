// Deterministic test images for the metric tests (test_metrics, test_flip)
// and samples for test_mann_whitney.
#pragma once

#include "harness_names.h"
#include "core/image.h"

#include <cmath>
#include <cstdint>

namespace cavity::test {

using namespace cavity::harness;

// A deterministic pseudo-random value in [0, 1) (a 32-bit LCG).
struct Lcg {
    uint32_t s;
    explicit Lcg(uint32_t seed) : s(seed) {}
    float next() {
        s = s * 1664525u + 1013904223u;
        return float(s >> 8) / float(1u << 24);
    }
};

// A smooth test pattern in [0.2, 0.8] with some structure for SSIM and FLIP.
inline HostImage pattern(int w, int h, int c) {
    HostImage img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k)
                img.at(x, y, k) = 0.5f + 0.3f * float(std::sin(0.3 * x + 0.7 * k) * std::cos(0.2 * y));
    return img;
}

inline HostImage withNoise(const HostImage& img, float amplitude, uint32_t seed) {
    HostImage out = img;
    Lcg rng(seed);
    for (float& v : out.pixels) v += amplitude * (2 * rng.next() - 1);
    return out;
}

}  // namespace cavity::test
