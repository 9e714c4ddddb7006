// How far a new image is from its baseline: the numbers the gate judges
// (gate.cpp) and the diff heat-map the HTML report shows (gate_report.cpp).
#pragma once

#include "images/namespace.h"
#include "core/image.h"
#include "result.h"

#include <array>

namespace cavity::images::metrics {

struct Report {
    double maxAbs, meanAbs, rmse, psnr;   // psnr in dB for signal range 1.0; +inf when identical
    double overThresholdShare;            // share of pixels with any channel |a-b| > threshold
    double ssim;                          // mean SSIM over channels, 1 = identical
    double flipMean = -1;                 // mean FLIP error (LDR), -1 when not computed
    long long nonFinite = 0;              // count of NaN/Inf pixels in the NEW image
    int firstNonFiniteX = -1, firstNonFiniteY = -1;
    int worstX, worstY;                   // pixel of maxAbs
    // Options::eightBit only: pixels whose colour differs by more than
    // Options::differingDelta 8-bit steps in any channel, and their share.
    // A change of one step over many pixels (a dither removed) moves the
    // means and SSIM too little to see; this count sees it (Skia Gold's
    // fuzzy matcher counts pixels the same way).
    long long differingPixels = 0;
    double differingShare = 0;
    int channelsCompared = 0;             // 3 for RGBA with a constant alpha (see compare)
};

struct Options {
    double threshold = 1.0 / 255.0;   // per-channel error counted by overThresholdShare
    bool flip = false;                // also compute flipMean (1, 3 or 4 channels, sRGB-encoded [0,1])
    bool eightBit = false;            // the images are 8-bit: count differingPixels
    int differingDelta = 0;           // 8-bit steps a pixel may move and still count as equal
};

// a = baseline, b = new; same shape required, else a BadInput error naming
// both shapes ("baseline is 320x180x1, new image is 160x90x1").
//
// Non-finite values: a value that is NaN or Inf in one image but not the same
// NaN/Inf in the other is a mismatch. It makes maxAbs +inf (worstX/Y = the
// first such pixel in row-major order), counts its pixel as over threshold,
// and is left out of meanAbs/rmse/psnr, which would otherwise all be NaN and
// so pass every "<=" check of the gate. SSIM and FLIP see non-finite values
// as 0. nonFinite counts the new image's pixels with any non-finite channel.
//
// Colour images are compared on their colour channels: an RGBA image whose
// alpha is one constant in both images is compared as RGB, since a constant
// channel that always matches would dilute every mean (by 1/4) and SSIM.
Result<Report> compare(const HostImage& baseline, const HostImage& candidate, const Options& = {});

// Mean SSIM over channels (Wang et al. 2004); exposed for the tests.
// Both images must have the same shape; non-finite values must be removed first.
double ssim(const HostImage& a, const HostImage& b);

// new - baseline per pixel (of the channel that moved most, with its sign)
// through diffColor((new - baseline) / scale), as an RGB image for the
// report's diff heat-map: the gate passes the tolerance's per-pixel
// threshold as the scale, so full colour is a pixel over it. Non-finite
// errors, and pixels the baseline lacks when the shapes differ, are magenta.
HostImage heatmap(const HostImage& baseline, const HostImage& candidate, double scale);

// The heat-map's colour map: s in [-1,1] (clamped; below 0 the new image is
// darker) to display (sRGB-encoded) RGB in [0,1], the values writeImage
// stores in a PNG as they are; NaN is magenta.
std::array<float, 3> diffColor(double s);

}  // namespace cavity::images::metrics
