// Hand-built G-buffers for the analytic tests: what the camera of camera.h
// sees of planes facing it, at chosen depths.
#pragma once

#include "harness_names.h"
#include "core/camera.h"
#include "core/image.h"

#include <functional>

namespace cavity::test {

using namespace cavity::harness;

struct GBuffer {
    HostImage position;   // view xyz, w = linear depth
    HostImage normal;     // view normal, w = 0
};

// depthAt(x, y) gives the linear depth of a camera-facing plane piece at
// each pixel (normal +Z, towards the camera); 0 means background.
inline GBuffer facingPlanes(int w, int h, const std::function<float(int, int)>& depthAt) {
    const auto f = frameUniforms(w, h, w, h);
    GBuffer g{HostImage(w, h, 4), HostImage(w, h, 4)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float d = depthAt(x, y);
            if (d <= 0) continue;
            const float nx = (float(x) + 0.5f) / float(w) * 2.0f - 1.0f;
            const float ny = (float(y) + 0.5f) / float(h) * 2.0f - 1.0f;
            g.position.at(x, y, 0) = nx * f.camera[0] * d;
            g.position.at(x, y, 1) = -ny * f.camera[1] * d;
            g.position.at(x, y, 2) = -d;
            g.position.at(x, y, 3) = d;
            g.normal.at(x, y, 2) = 1.0f;
        }
    return g;
}

}  // namespace cavity::test
