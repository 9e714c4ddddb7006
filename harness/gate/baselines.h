// What the gate compares against, all under baselines/:
//   matrices.json           named matrices of configurations (`cavity gate --matrix NAME`)
//   manifest.json           per-pipeline tolerances for each image metric, with per-device overrides
//   budgets.json            per-device-class timing budgets (median ms per pass) by configuration id
//   images/<baseline key>/<image>.exr|png
// Baseline keys, the checked images and the matrices are in matrix.h.
#pragma once

#include "gate/namespace.h"
#include "core/config.h"
#include "plan/matrix.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cavity::gate {

// ---- manifest.json ----
struct Tolerance {
    double maxAbs = 0.02;
    double meanAbs = 0.002;
    double rmse = 0.005;
    double psnrMin = 40;
    double pixelThreshold = 0.01;       // per-pixel error counted by overThresholdShare
    double overThresholdShare = 0.01;
    double ssimMin = 0.98;
    double flipMeanMax = 0.02;
    // 8-bit images: at most this share of pixels may differ by more than
    // differingDelta steps in any colour channel (1 allows every pixel).
    double differingDelta = 0;
    double differingShareMax = 1;
    // 0: the tolerances hold for an image of any size. N: mean abs, RMSE and
    // the share over the threshold are stated for an image of N pixels, for
    // noise that is a count of pixels rather than a share of them (the CPU
    // renderers' flipped samples, docs/gate.md "Subtle errors"); sizedFor()
    // scales them to an image's own size.
    double sizedForPixels = 0;
};
// `t` for an image of `pixels` pixels: where t.sizedForPixels is N > 0, mean
// abs and the share over the threshold times N / pixels (the share at most
// 1), RMSE times its square root, and sizedForPixels = pixels, so that
// sizing again for the same image changes nothing.
Tolerance sizedFor(Tolerance t, long long pixels);
struct Manifest {
    std::map<std::string, Tolerance> pipelines;   // by AO kernel name; "*" is the default
    // A device's own tolerances. By default (scope "baselines") they apply
    // only where its image is judged against the stored baselines, which
    // another device rendered: they allow for that device's rounding. Scope
    // "all" applies them against every reference, its own class's included:
    // for a renderer whose own renders are the stored baselines, where they
    // are its own noise (the CPU renderers, docs/gate.md "Subtle errors").
    struct DeviceOverride {
        std::string pattern;
        std::map<std::string, std::map<std::string, double>> pipelines;
        bool everyReference = false;
    };
    std::vector<DeviceOverride> devices;
    std::map<std::string, std::map<std::string, double>> rawPipelines;   // as written, for overrides
    // The tolerances for an image of `deviceName` judged against the stored
    // baselines (ownClass false) or against its own class's reference.
    Tolerance forPipeline(const std::string& kernel, const std::string& deviceName, bool ownClass = false) const;
};
Result<Manifest> loadManifest(const std::string& path);

// ---- budgets.json ----
struct Budgets {
    struct Device { std::string pattern; std::map<std::string, std::map<std::string, double>> configs; };
    std::vector<Device> devices;
    // The budget of one pass of one configuration on this device, if any.
    std::optional<double> find(const std::string& deviceName, const std::string& id, const std::string& pass) const;
    // The first entry whose pattern the device's name holds, if any.
    const Device* entryFor(const std::string& deviceName) const;
};
Result<Budgets> loadBudgets(const std::string& path);

}  // namespace cavity::gate
