// Quality against the ground truth: every AO kernel's mean absolute error
// against the ray-traced reference (kernels/ao/ground_truth/ground_truth.glsl) on the same
// G-buffer, the measure the issues quote and `cavity quality` prints.
//
// The compared image is what the AO pipeline hands to the bilateral blur,
// with the bilateral off (--blur 0, unless QualityOptions::blur says else): the raw AO, after the 4x4 box blur for
// the hemisphere kernel (that blur is part of the method, seed 004), after
// the bilateral upsample at half resolution. Background pixels (no
// surface) are left out.
#pragma once

#include "measure/namespace.h"
#include "backend.h"
#include "core/config.h"
#include "core/image.h"
#include "result.h"

#include <map>
#include <string>
#include <memory>
#include <optional>
#include <vector>

namespace cavity::measure {

struct QualityOptions {
    std::vector<std::string> scenes{"corner", "slats"};
    std::vector<std::string> kernels;        // empty: every kernel of role "ao"
    std::vector<int> samples{16, 64};
    int width = 160, height = 90;
    int rays = 1024;                         // the ground truth's
    bool half = false;
    gpu::Stage stage = gpu::Stage::Compute;
    // The reach every kernel and the truth use. "seed": each kernel at its
    // own declared default (the screen-space kernels' R = 0.5, the SDF
    // kernels' seed constants, e.g. sdf_multiscale's 6.4), the truth at
    // 0.5. "shared": every kernel and the truth at `radius`, which compares
    // estimators of one quantity rather than of each seed's.
    bool sharedReach = false;
    double radius = 0.5;
    // The pipeline's blur radius before the comparison (--blur): 0, the
    // default, compares the raw AO; r > 0 the AO after the kernel's own blur
    // (the 2-D bilateral, or alchemy_fast's separable pair), against the same
    // unblurred truth, which is how a blur's cost in accuracy shows.
    int blur = 0;
    // Switches of the fast kernels (--exact 0, --interleave 4): each set on
    // every kernel that declares it, the others left as they are.
    kernels::ParamValues switches;
    // --kernel-source: kernels/NAME replaced by a file's text in every
    // kernel's pipeline (the ground truth keeps its own).
    std::map<std::string, std::string> overrides;   // pipeline::SourceOverrides
    // Keep each row's AO image and its scene's truth (QualityRow::ao,
    // ::truth), for the error maps of `quality --out`.
    bool keepImages = false;
};

// `c` with the switches its kernel declares.
void applySwitches(RunConfig& c, const kernels::ParamValues& switches);
// Fails naming the first switch that no measured configuration's kernel
// declares: a flag that changes nothing measured is a mistake.
Status checkSwitchesUsed(const kernels::ParamValues& switches, const std::vector<RunConfig>& measured);

struct GroundTruth;

struct QualityRow {
    std::string scene, kernel;
    int samples = 0;
    double meanAbsError = 0;   // over surface pixels, AO in [0, 1]
    // The MAE's interval between the kIntervalLow and kIntervalHigh
    // quantiles of a bootstrap over kTileSide-pixel tiles of the image (a
    // resample draws whole tiles, so that neighbouring pixels' correlated
    // errors stay together), percentile method.
    double maeLow = 0, maeHigh = 0;
    double maxAbsError = 0;
    double meanAo = 0, meanTruth = 0;   // signed bias is meanAo - meanTruth
    long long pixels = 0;
    // With a --kernel-source edit that changed this row's AO: the MAE of the
    // same configuration with the committed kernels.
    std::optional<double> committedMae;
    // Per kTileSide tile in row order (empty ones too, so that two rows of
    // one scene and size line up): summed |error| and surface pixels.
    std::vector<std::pair<double, long long>> tiles;
    std::shared_ptr<const HostImage> ao;          // QualityOptions::keepImages
    std::shared_ptr<const GroundTruth> truth;
};
constexpr int kTileSide = 8;
constexpr int kBootstrapDraws = 1000;
// The interval's quantiles: the central share the reports print as its confidence.
constexpr double kIntervalLow = 0.025, kIntervalHigh = 0.975;

// The ground-truth AO of a scene at a size on one backend, and the mask of
// surface pixels (1 where the G-buffer holds a surface).
struct GroundTruth {
    HostImage ao, surface;
};
// radius <= 0: the ground truth's declared default reach.
Result<GroundTruth> groundTruth(gpu::Backend& gpu, const std::string& scene, int width, int height, int rays,
                                double radius = 0);

// MAE of one AO image against the truth over its surface pixels.
QualityRow compareToTruth(const HostImage& ao, const GroundTruth& truth);
// The interval (kIntervalLow to kIntervalHigh) of MAE(b) - MAE(a) for two rows of one scene and size,
// by a paired bootstrap over their tiles (one resample of tile indices for
// both): when it holds 0 the two kernels cannot be told apart.
std::pair<double, double> maeDifference(const QualityRow& a, const QualityRow& b);

Result<std::vector<QualityRow>> measureQuality(gpu::Backend& gpu, const QualityOptions& options);

}  // namespace cavity::measure