// Analytic scenes for the quality tests: solid axis-aligned boxes in a
// world frame, seen by the harness camera (harness/core/camera.h: fovY 60
// degrees, looking down -Z in view space) from any eye, target and roll.
// Planes at any tilt and roll are one box seen from a rotated camera.
//
// From the boxes alone, in double precision and without any kernel code:
//   * the G-buffer the import path takes (view-space position and normal
//     of the first hit through each pixel centre; background where no box
//     is hit), and
//   * the ground truth the kernels estimate: the cosine-weighted fraction of
//     the normal's hemisphere from which a ray escapes every box within the
//     reach R, exact up to the ray count (a Fibonacci lattice, as
//     kernels/ao/ground_truth/ground_truth.glsl uses), and
//   * the best a single depth layer can do: the same rays marched finely
//     through the G-buffer, each step blocked when it lies behind the
//     recorded surface's plane (everything behind the first surface is taken
//     as solid, which is all one depth layer can say). Where the truth and
//     this differ, no screen-space kernel can close the gap.
#pragma once

#include "harness_names.h"
#include "core/config.h"

#include <functional>
#include <string>
#include <vector>

namespace cavity::test::analytic {

using namespace cavity::harness;

struct V3 {
    double x = 0, y = 0, z = 0;
};

struct Box {
    V3 lo, hi;
};

struct Camera {
    V3 eye, target;
    double rollDegrees = 0;
};

struct Scene {
    std::string name;
    std::vector<Box> boxes;
    Camera camera;
};

struct Hit {
    bool surface = false;
    V3 world, normal;      // world position and outward unit normal
};

// One scene rendered at a size: what each pixel sees, its G-buffer in the
// harness's layout (config.h GBufferImages) and the per-pixel truth.
struct Frame {
    int width = 0, height = 0;
    std::vector<Hit> hits;          // row 0 the top
    GBufferImages gbuffer;
    HostImage truth;                // 1 channel; 1 at background
    Hit at(int x, int y) const { return hits[size_t(y) * width + x]; }
};

// rays: truth rays per pixel.
Frame render(const Scene& scene, int width, int height, double reach, int rays);

// The single-layer bound at one pixel: `rays` directions, `steps` points
// along each out to `reach`.
double singleLayerVisibility(const Frame& f, int x, int y, double reach, int rays, int steps);

}  // namespace cavity::test::analytic
