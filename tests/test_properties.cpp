// Properties the seeds state, checked on the GPU kernels of both backends.
#include "blur_weights.h"
#include "gpu_fixture.h"
#include "pipeline/kernel_runner.h"
#include "pipeline/pipeline.h"
#include "synthetic.h"

#include <cmath>
#include <map>

namespace cavity::test {
namespace {

constexpr int W = 160, H = 90;

class Properties : public GpuTest {
protected:
    std::vector<HostImage> run(const std::string& kernel, std::vector<const HostImage*> inputs,
                               kernels::ParamValues params = {}) {
        KernelRun r;
        r.kernel = kernels::find(kernel);
        EXPECT_NE(r.kernel, nullptr) << kernel;
        r.params = params;
        r.width = W;
        r.height = H;
        r.inputs = std::move(inputs);
        auto out = runKernel(gpu(), r);
        EXPECT_TRUE(out) << (out ? "" : out.error().message);
        return out ? *out : std::vector<HostImage>{};
    }
};

// McGuire et al., HPG 2011: a sample in the tangent plane adds nothing
// (N·ω = 0 is under the bias), so a plane facing the camera is fully open.
TEST_P(Properties, AlchemyOnAPlaneFacingTheCameraIsOne) {
    const GBuffer g = facingPlanes(W, H, [](int, int) { return 3.0f; });
    for (int n : {1, 16, 64}) {
        const auto ao = run("alchemy", {&g.position, &g.normal}, {{"samples", n}});
        ASSERT_EQ(ao.size(), 1u);
        for (float v : ao[0].pixels) ASSERT_EQ(v, 1.0f) << "n = " << n;
    }
}

// The blur divides by 2·sum − w0 so that the symmetric kernel sums to one
// (McGuire et al., HPG 2011); a wrong divisor shifts brightness with radius.
TEST(GaussianWeights, SymmetricKernelSumsToOneForEveryRadius) {
    for (int r = 1; r <= 32; ++r) {
        const auto w = kernels::gaussianWeights(r);
        ASSERT_EQ(int(w.size()), r + 1);
        double sum = w[0];
        for (int i = 1; i <= r; ++i) sum += 2.0 * w[size_t(i)];
        EXPECT_NEAR(sum, 1.0, 1e-6) << "radius " << r;
        for (int i = 1; i <= r; ++i) EXPECT_LT(w[size_t(i)], w[size_t(i - 1)]) << "radius " << r;
    }
}

TEST_P(Properties, BilateralBlurOfAConstantIsThatConstant) {
    // A G-buffer with depth steps and creases: the corner scene itself.
    RunConfig c;
    c.api = api();
    c.width = W;
    c.height = H;
    auto chain = PassChain::create(gpu(), c);
    ASSERT_TRUE(chain) << chain.error().message;
    gpu().beginFrame();
    (*chain)->record();
    ASSERT_TRUE(gpu().endFrame().ok());
    auto position = (*chain)->read("position");
    auto normal = (*chain)->read("normal");
    ASSERT_TRUE(position && normal);
    const HostImage constant(W, H, 1, 0.375f);   // exact in half precision
    for (int radius : {1, 4, 13, 32}) {
        const auto out = run("blur_bilateral", {&constant, &*position, &*normal}, {{"blur", radius}});
        ASSERT_EQ(out.size(), 1u);
        const Diff d = diff(constant, out[0], 2.5e-4);
        EXPECT_EQ(d.over, 0) << "radius " << radius << ": max " << d.maxAbs << " at (" << d.worstX << ","
                             << d.worstY << ")";
    }
}

TEST_P(Properties, BilateralBlurDoesNotCarryAoAcrossADepthStep) {
    // Left half at depth 2 with AO 1, right half at depth 6 with AO 0.
    const int edge = W / 2;
    const GBuffer g = facingPlanes(W, H, [&](int x, int) { return x < edge ? 2.0f : 6.0f; });
    HostImage ao(W, H, 1);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) ao.at(x, y) = x < edge ? 1.0f : 0.0f;
    const auto out = run("blur_bilateral", {&ao, &g.position, &g.normal}, {{"blur", 8}});
    ASSERT_EQ(out.size(), 1u);
    for (int y = 0; y < H; ++y) {
        EXPECT_GE(out[0].at(edge - 1, y), 0.999f) << "row " << y;
        EXPECT_LE(out[0].at(edge, y), 0.001f) << "row " << y;
    }
    // Radius 0 passes the input through.
    const auto same = run("blur_bilateral", {&ao, &g.position, &g.normal}, {{"blur", 0}});
    EXPECT_EQ(diff(ao, same.at(0)).maxAbs, 0.0);
}

TEST_P(Properties, AddingAnOccluderNeverRaisesAo) {
    // A floor plane at depth 4, then the same with a block 0.3 closer in the middle.
    const GBuffer open = facingPlanes(W, H, [](int, int) { return 4.0f; });
    auto inBlock = [](int x, int y) { return x >= 60 && x < 100 && y >= 30 && y < 60; };
    const GBuffer blocked = facingPlanes(W, H, [&](int x, int y) { return inBlock(x, y) ? 3.7f : 4.0f; });
    const kernels::ParamValues p{{"samples", 32}, {"radius", 1.0}};
    const auto a = run("alchemy", {&open.position, &open.normal}, p);
    const auto b = run("alchemy", {&blocked.position, &blocked.normal}, p);
    ASSERT_TRUE(a.size() == 1 && b.size() == 1);
    int darker = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (inBlock(x, y)) continue;
            ASSERT_LE(b[0].at(x, y), a[0].at(x, y)) << "(" << x << "," << y << ")";
            darker += b[0].at(x, y) < a[0].at(x, y) - 0.01f;
        }
    EXPECT_GT(darker, 100) << "the block should darken the floor around it";
}

CAVITY_ALL_BACKENDS(Properties);

}  // namespace
}  // namespace cavity::test

namespace cavity::test {
namespace {

class ScreenSpaceProperties : public GpuTest {
protected:
    std::vector<HostImage> run(const std::string& kernel, std::vector<const HostImage*> inputs,
                               kernels::ParamValues params = {}, int w = W, int h = H) {
        KernelRun r;
        r.kernel = kernels::find(kernel);
        EXPECT_NE(r.kernel, nullptr) << kernel;
        r.params = params;
        r.width = w;
        r.height = h;
        r.inputs = std::move(inputs);
        auto out = runKernel(gpu(), r);
        EXPECT_TRUE(out) << (out ? "" : out.error().message);
        return out ? *out : std::vector<HostImage>{};
    }
    HostImage constant(const std::string& name) {
        const auto* c = kernels::findConstant(name);
        const auto levels = c->make({});
        HostImage img(levels[0].width, levels[0].height, gpu::channelCount(c->format));
        img.pixels = levels[0].pixels;
        return img;
    }
};

// the hemisphere SSAO lesson (docs/kernels.md): a 4x4 box of offsets -1.5..+1.5 averages exactly
// one period of the rotation tile, so a pure tile pattern comes out flat.
TEST_P(ScreenSpaceProperties, BoxBlurOfTheNoiseTileIsFlat) {
    HostImage tiled(W, H, 1);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) tiled.at(x, y) = float((x % 4) * 4 + (y % 4)) / 15.0f;   // 16 distinct values
    const auto out = run("blur_box", {&tiled});
    ASSERT_EQ(out.size(), 1u);
    const float mean = 0.5f;
    for (float v : out[0].pixels) ASSERT_NEAR(v, mean, 2.5e-4);
}

// Ritschel et al., I3D 2009: with nothing in the hemisphere every sample is
// visible, and the bounce is the sender's albedo times its light, so a black
// albedo sends nothing.
TEST_P(ScreenSpaceProperties, SsdoSeesEverythingOnAnOpenPlaneAndBlackSendsNoBounce) {
    const GBuffer g = facingPlanes(W, H, [](int, int) { return 3.0f; });
    const HostImage sky = constant("sky");
    KernelRun r;
    r.kernel = kernels::find("ssdo");
    r.width = W;
    r.height = H;
    r.inputs = {&g.position, &g.normal, &sky};
    r.inputFormats = {gpu::Format::RGBA32F, gpu::Format::RGBA16F, gpu::Format::RGBA32F};
    auto direct = runKernel(gpu(), r);
    ASSERT_TRUE(direct) << direct.error().message;
    for (float v : (*direct)[0].pixels) ASSERT_EQ(v, 1.0f);
    // An occluding step, black everywhere: visibility drops, the bounce stays 0.
    const GBuffer step = facingPlanes(W, H, [](int x, int) { return x < W / 2 ? 3.0f : 2.7f; });
    const HostImage black(W, H, 4, 0.0f);
    const auto indirect = run("ssdo_indirect", {&step.position, &step.normal, &black, &(*direct)[1]});
    ASSERT_EQ(indirect.size(), 1u);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(indirect[0].at(x, y, c), 0.0f) << "(" << x << "," << y << ")";
}

TEST_P(ScreenSpaceProperties, HemisphereOnAPlaneFacingTheCameraIsOne) {
    // Hardware depth of a camera-facing plane, as depth_from_position makes it.
    const GBuffer g = facingPlanes(W, H, [](int, int) { return 3.0f; });
    const auto depth = run("depth_from_position", {&g.position});
    ASSERT_EQ(depth.size(), 1u);
    const HostImage noise = constant("noise4x4");
    const auto ao = run("hemisphere", {&depth[0], &g.normal, &noise}, {{"samples", 32}});
    ASSERT_EQ(ao.size(), 1u);
    for (float v : ao[0].pixels) ASSERT_GE(v, 0.999f);
}

// Half resolution must not bleed AO across a silhouette: with a depth step and
// AO 1 on one side, 0 on the other, the bilateral upsample keeps each side's own
// value on every full-resolution pixel (McGuire et al., HPG 2011 warns of halos).
TEST_P(ScreenSpaceProperties, HalfResolutionUpsampleDoesNotBleedAcrossASilhouette) {
    const int edge = W / 2 + 1;   // odd, so the edge falls inside a 2x2 block
    const GBuffer full = facingPlanes(W, H, [&](int x, int) { return x < edge ? 2.0f : 6.0f; });
    KernelRun down;
    down.kernel = kernels::find("downsample_depth");
    down.width = W / 2;
    down.height = H / 2;
    down.srcWidth = W;
    down.srcHeight = H;
    down.inputs = {&full.position, &full.normal};
    auto half = runKernel(gpu(), down);
    ASSERT_TRUE(half) << half.error().message;
    HostImage aoHalf(W / 2, H / 2, 1);
    for (int y = 0; y < H / 2; ++y)
        for (int x = 0; x < W / 2; ++x) aoHalf.at(x, y) = (*half)[0].at(x, y, 3) < 4.0f ? 1.0f : 0.0f;
    KernelRun up;
    up.kernel = kernels::find("upsample_bilateral");
    up.width = W;
    up.height = H;
    up.inputs = {&aoHalf, &(*half)[0], &full.position, &full.normal, &(*half)[1]};
    auto ao = runKernel(gpu(), up);
    ASSERT_TRUE(ao) << ao.error().message;
    long long wrong = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) wrong += std::fabs((*ao)[0].at(x, y) - (x < edge ? 1.0f : 0.0f)) > 1e-3f;
    EXPECT_EQ(wrong, 0) << "pixels that took AO from the other side of the step";
}

// On the scene: inside a band around silhouettes (a neighbour within 2 px
// more than a tenth away in depth), half resolution stays close to full.
// Bound 0.05 mean absolute difference: both scenes keep under it with the
// bilateral upsample, and slats does not with a bilinear one, so the bound
// tells the two apart.
TEST_P(ScreenSpaceProperties, HalfResolutionStaysCloseToFullAtSilhouettes) {
    for (const std::string scene : {"corner", "slats"}) {
        std::map<bool, HostImage> ao;
        HostImage position;
        for (bool halfRes : {false, true}) {
            RunConfig c;
            c.api = api();
            c.width = 320;
            c.height = 180;
            c.half = halfRes;
            ASSERT_TRUE(setParam(c, "scene", scene).ok());
            auto chain = PassChain::create(gpu(), c);
            ASSERT_TRUE(chain) << chain.error().message;
            gpu().beginFrame();
            (*chain)->record();
            ASSERT_TRUE(gpu().endFrame().ok());
            ao[halfRes] = *(*chain)->read("ao_blur");
            position = *(*chain)->read("position");
        }
        double sum = 0;
        long long n = 0;
        for (int y = 2; y < 178; ++y)
            for (int x = 2; x < 318; ++x) {
                const float d = position.at(x, y, 3);
                if (d <= 0) continue;
                bool band = false;
                for (int dy = -2; dy <= 2 && !band; ++dy)
                    for (int dx = -2; dx <= 2 && !band; ++dx) {
                        const float e = position.at(x + dx, y + dy, 3);
                        band = e <= 0 || std::fabs(e - d) > 0.1f * d;
                    }
                if (!band) continue;
                sum += std::fabs(ao[true].at(x, y) - ao[false].at(x, y));
                ++n;
            }
        ASSERT_GT(n, 100) << scene;
        EXPECT_LT(sum / double(n), 0.05) << scene << ": mean |half - full| in the silhouette band";
    }
}

// A plane occludes nothing (N.omega = 0 under the bias), at half
// resolution too: the fast kernels rebuild each position from the pyramid's
// depth on the half texel's own ray, so that depth must lie on the surface
// there (include/downsample.glsl, halfRayDepth). With the copied full
// texel's depth both kernels darkened the open floor at 160x90 half
// (study 2026-12-07_half_ray_depth). alchemy_fast's estimator is exact
// on a plane, so every pixel is 1; hemisphere_fast keeps the copied depth
// where the floor is nearly edge-on to the ray, so its mean is bounded.
TEST_P(ScreenSpaceProperties, FastKernelsAtHalfResolutionLeaveAPlaneOpen) {
    for (const std::string kernel : {"alchemy_fast", "hemisphere_fast"}) {
        RunConfig c;
        c.api = api();
        c.width = 160;
        c.height = 90;
        c.half = true;
        c.kernel = kernel;
        ASSERT_TRUE(setParam(c, "scene", "open").ok());
        auto chain = PassChain::create(gpu(), c);
        ASSERT_TRUE(chain) << chain.error().message;
        gpu().beginFrame();
        (*chain)->record();
        ASSERT_TRUE(gpu().endFrame().ok());
        const HostImage ao = *(*chain)->read("ao");
        ASSERT_EQ(ao.width, 80) << "the raw AO at half size";
        double occlusion = 0;
        for (int y = 0; y < ao.height; ++y)
            for (int x = 0; x < ao.width; ++x) {
                occlusion += 1.0 - ao.at(x, y);
                if (kernel == "alchemy_fast") {
                    ASSERT_EQ(ao.at(x, y), 1.0f) << kernel << " (" << x << "," << y << ")";
                }
            }
        EXPECT_LT(occlusion / double(ao.width * ao.height), 0.005) << kernel << ": mean 1 - AO on the open floor";
    }
}

CAVITY_ALL_BACKENDS(ScreenSpaceProperties);

}  // namespace
}  // namespace cavity::test
