// Two screen-space artefacts of the hemisphere pipeline that we were asked
// to fix or show inherent, measured against the ray-traced ground truth on
// the corner scene (floor, two walls, a sphere at the crease), 160x90, n16,
// the AO where `cavity quality` reads it (after the 4x4 box, bilateral off).
//
//  * The ring round the sphere: seed 004's 4x4 box blur ignores depth and
//    averages the sphere's open outline with the darker wall behind it, a
//    grey line along the outline. blur_box_depth (depth_aware_box) keeps the
//    box to one surface. On the pixels in front of a depth step of more
//    than R / 2 within their box window (the sphere's outline), the error
//    against the truth must fall: to at most half for hemisphere_cosine,
//    whose raw AO follows the truth so that what is left there is the
//    blur's (lavapipe: 0.100 -> 0.039), and below the seed box's for the
//    seed hemisphere, whose own estimator is 0.1 off there
//    (0.118 -> 0.106). The wall pixels behind the outline are printed, not
//    bounded: there the depth-aware box leaves the raw estimator's own
//    error, which the seed's box had partly averaged away (README, Kernels).
//  * The half-resolution haze: a half texel holds a real full texel's
//    position, half a full texel off its own centre ray, and the kernel
//    rebuilt positions on its own ray from that depth: points stood off
//    their walls and shadowed each other. depth_from_position_half puts the
//    depth back on the half texel's ray. On the pixels the truth calls open
//    (nothing within R), the half-resolution AO must be as open as the full
//    resolution's, within 0.01 (lavapipe: 0.9991 full, 0.9987 half for
//    hemisphere; over all pixels the half-resolution MAE went from 0.083 to
//    0.068, the full resolution's 0.068).
#include "gpu_fixture.h"
#include "pipeline/pipeline.h"
#include "measure/quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace cavity::test {
namespace {

constexpr int kW = 160, kH = 90;

class Silhouettes : public GpuTest {
protected:
    const GroundTruth& truth() {
        if (!truth_) {
            auto t = groundTruth(gpu(), "corner", kW, kH, 1024, 0.5);
            EXPECT_TRUE(t) << t.error().message;
            if (t) truth_ = std::move(*t);
        }
        return *truth_;
    }
    std::map<std::string, HostImage> render(const std::string& kernel, bool half, double depthAwareBox) {
        RunConfig c;
        c.api = api();
        c.kernel = kernel;
        c.width = kW;
        c.height = kH;
        c.half = half;
        c.params["blur"] = 0;
        c.params["samples"] = 16;
        c.params["depth_aware_box"] = depthAwareBox;
        EXPECT_TRUE(setParam(c, "scene", "corner").ok());
        auto images = renderImages(gpu(), c, {"ao_blur", "position"});
        EXPECT_TRUE(images) << images.error().message;
        return images ? std::move(*images) : std::map<std::string, HostImage>{};
    }

private:
    std::optional<GroundTruth> truth_;
};

TEST_P(Silhouettes, DepthAwareBoxLeavesNoRingAtSilhouettes) {
    const GroundTruth& t = truth();
    for (const std::string kernel : {"hemisphere", "hemisphere_cosine"}) {
        auto seed = render(kernel, false, 0);
        auto aware = render(kernel, false, 1);
        ASSERT_EQ(seed["ao_blur"].width, kW);
        ASSERT_EQ(aware["ao_blur"].width, kW);
        const HostImage& position = seed["position"];
        double errSeed = 0, errAware = 0, biasSeed = 0, biasAware = 0, nearSeed = 0, nearAware = 0;
        int ring = 0, nearCount = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                if (t.surface.at(x, y) == 0.0f) continue;
                // The box's window (blur_box.glsl): x - 2 .. x + 1, clamped inwards.
                const int sx = std::clamp(x - 2, 0, kW - 4), sy = std::clamp(y - 2, 0, kH - 4);
                bool behind = false, front = false;
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 4; ++i) {
                        const float d = position.at(sx + i, sy + j, 3);
                        behind |= d > 0.0f && position.at(x, y, 3) - d > 0.25f;
                        front |= d > 0.0f && d - position.at(x, y, 3) > 0.25f;
                    }
                const double es = seed["ao_blur"].at(x, y) - t.ao.at(x, y), ea = aware["ao_blur"].at(x, y) - t.ao.at(x, y);
                if (front && !behind) {
                    ++nearCount;
                    nearSeed += std::fabs(es);
                    nearAware += std::fabs(ea);
                }
                if (!behind) continue;
                ++ring;
                errSeed += std::fabs(es);
                errAware += std::fabs(ea);
                biasSeed += es;
                biasAware += ea;
            }
        ASSERT_GT(nearCount, 100) << "the corner scene has no silhouettes to test";
        errSeed /= ring, errAware /= ring, biasSeed /= ring, biasAware /= ring;
        nearSeed /= std::max(nearCount, 1), nearAware /= std::max(nearCount, 1);
        std::printf("%-4s %-18s %d pixels behind a silhouette: error %.4f (seed box), %.4f (depth-aware); bias %.4f, %.4f; "
                    "%d in front: error %.4f, %.4f\n",
                    gpu::apiName(api()), kernel.c_str(), ring, errSeed, errAware, biasSeed, biasAware, nearCount, nearSeed, nearAware);
        if (kernel == "hemisphere_cosine") {
            EXPECT_LE(nearAware, 0.5 * nearSeed) << kernel;
        } else {
            EXPECT_LT(nearAware, nearSeed) << kernel;
        }
    }
}

TEST_P(Silhouettes, HalfResolutionOpenWallsAreAsOpenAsFullResolution) {
    const GroundTruth& t = truth();
    for (const std::string kernel : {"hemisphere", "hemisphere_cosine"}) {
        auto full = render(kernel, false, 0);
        auto half = render(kernel, true, 0);
        ASSERT_EQ(half["ao_blur"].width, kW);
        double meanFull = 0, meanHalf = 0;
        int open = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                if (t.surface.at(x, y) == 0.0f || t.ao.at(x, y) < 1.0f) continue;
                ++open;
                meanFull += full["ao_blur"].at(x, y);
                meanHalf += half["ao_blur"].at(x, y);
            }
        ASSERT_GT(open, 1000) << "the corner scene has no open wall";
        meanFull /= open, meanHalf /= open;
        std::printf("%-4s %-18s %d open pixels: mean AO %.4f full, %.4f half\n", gpu::apiName(api()), kernel.c_str(),
                    open, meanFull, meanHalf);
        EXPECT_NEAR(meanHalf, meanFull, 0.01) << kernel;
    }
}

CAVITY_ALL_BACKENDS(Silhouettes);

}  // namespace
}  // namespace cavity::test
