// LDR-FLIP: how visible the difference between two LDR images is to a viewer
// flipping between them. P. Andersson, J. Nilsson, T. Akenine-Möller,
// M. Oskarsson, K. Åström, M. D. Fairchild, "FLIP: A Difference Evaluator for
// Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020).
#pragma once

#include "images/namespace.h"
#include "core/image.h"
#include "result.h"

namespace cavity::images::flip {

// Pixels per degree of visual angle for a viewer at distanceM from a monitor
// widthM wide showing widthPx pixels across.
constexpr double pixelsPerDegree(double distanceM, double widthM, double widthPx) {
    return distanceM * (widthPx / widthM) * (3.14159265358979323846 / 180.0);
}

// The paper's default viewing conditions: 0.7 m from a 0.7 m wide 3840-pixel
// monitor, 67.02 pixels per degree; 67 is what callers pass.
inline constexpr double kDefaultPixelsPerDegree = 67.0;

struct FlipResult {
    HostImage errorMap;   // 1 channel, per-pixel error in [0, 1]
    double mean = 0;      // mean of errorMap
};

// reference and test: sRGB-encoded images of the same shape with 1 (grey,
// replicated to RGB), 3 or 4 (alpha ignored) channels; values are clamped to
// [0, 1] and non-finite values read as 0.
cavity::Result<FlipResult> ldrFlip(const HostImage& reference, const HostImage& test,
                                   double pixelsPerDegree = kDefaultPixelsPerDegree);

}  // namespace cavity::images::flip
