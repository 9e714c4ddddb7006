// A host-side float image: what readback returns, what the CPU references
// compute, what the baselines and metrics compare. Rows top to bottom.
#pragma once

#include <cstddef>
#include <vector>

namespace cavity::core {

struct HostImage {
    int width = 0;
    int height = 0;
    int channels = 1;
    std::vector<float> pixels;   // width * height * channels

    HostImage() = default;
    HostImage(int w, int h, int c, float fill = 0.0f)
        : width(w), height(h), channels(c), pixels(size_t(w) * h * c, fill) {}

    float& at(int x, int y, int c = 0) { return pixels[(size_t(y) * width + x) * channels + c]; }
    float at(int x, int y, int c = 0) const { return pixels[(size_t(y) * width + x) * channels + c]; }
    // Clamp-to-edge fetch, as the kernels' samplers do.
    float clamped(int x, int y, int c = 0) const {
        x = x < 0 ? 0 : (x >= width ? width - 1 : x);
        y = y < 0 ? 0 : (y >= height ? height - 1 : y);
        return at(x, y, c);
    }
    bool sameShape(const HostImage& o) const {
        return width == o.width && height == o.height && channels == o.channels;
    }
};

}  // namespace cavity::core