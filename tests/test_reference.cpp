// Every kernel on the GPU against its CPU reference, on both backends, both
// scenes, at 160x90 and 320x180. Each pass is checked on its own: the CPU
// reference gets the very inputs the GPU pass read back, so an error in one
// kernel cannot hide in, or be blamed on, another.
//
// Tolerances, and why:
//  * AO (R16F, values in [0, 1]): 1e-3. Half floats round to within 2.4e-4
//    near 1 and the CPU result is rounded the same way; the rest is float
//    transcendental differences (sin/cos/exp/pow) between drivers and libm.
//  * Composite (RGBA8): one 8-bit step, since the dithered value can sit on a
//    rounding boundary.
//  * G-buffer: see kGbuffer below; the ray march is iterative, so a ray that
//    grazes a silhouette may hit on one side and miss on the other.
#include "core/camera.h"
#include "pipeline/config_id.h"
#include "gpu_fixture.h"
#include "pipeline/kernel_runner.h"
#include "pipeline/pipeline.h"
#include "package/package.h"
#include "reference/reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace cavity::test {
namespace {

struct Case {
    std::string scene;
    int width, height;
    std::string kernel = "alchemy";
    bool half = false;
    gpu::Stage stage = gpu::Stage::Compute;
    bool fusedTail = false;
    int interleave = 1;   // the AO pass's interleaved layers per axis
    int samples = 0;      // 0: the kernel's default
    int blur = -1;        // the blur radius; -1: the kernel's default
    // A kernel that declares `exact` runs with it 1, the CPU reference's
    // arithmetic, which every pixel matches. Its default, the GPU's own
    // arithmetic, is held to the precision contract's tolerance instead
    // (DefaultFastKernelsHoldTheStatedTolerance).
    bool exact = true;
    int steps = 0;   // points a ray (hemisphere_fast) or a direction (ssdo_fast); 0: the kernel's default
};

class KernelVsReference : public GpuTest {};

struct Tolerance {
    double maxAbs;
    double outlierFraction;   // share of pixels allowed over maxAbs
};

Tolerance toleranceFor(const std::string& kernel) {
    if (kernel == "gbuffer_sdf") return {2e-3, 0.003};
    if (kernel == "composite") return {1.0 / 255.0 + 1e-6, 0.0};
    return {1e-3, 0.0};
}

// The chain of `c` on `gpu`, one frame of it recorded and finished.
Result<std::unique_ptr<PassChain>> recordedChain(gpu::Backend& gpu, const RunConfig& c) {
    CAVITY_ASSIGN(auto chain, PassChain::create(gpu, c));
    gpu.beginFrame();
    chain->record();
    CAVITY_TRY(gpu.endFrame());
    return chain;
}

// `kernel` on corner at 160x90, every other setting its default.
RunConfig smallConfig(gpu::Api api, const std::string& kernel, bool half = false) {
    RunConfig c;
    c.api = api;
    c.width = 160;
    c.height = 90;
    c.kernel = kernel;
    c.half = half;
    return c;
}

// The AO, blurred AO and composite images of one recorded frame of `c`.
Result<std::map<std::string, HostImage>> frameImages(gpu::Backend& gpu, const RunConfig& c) {
    CAVITY_ASSIGN(auto chain, recordedChain(gpu, c));
    std::map<std::string, HostImage> images;
    for (const std::string name : {"ao", "ao_blur", "color"}) {
        CAVITY_ASSIGN(images[name], chain->read(name));
    }
    return images;
}

// The CPU reference of one pass of a recorded chain, fed the very images the
// GPU pass read (CPU-made constants at level 0); outputs in its order.
Result<std::vector<HostImage>> referenceOf(PassChain& chain, const PassSpec& pass, const RunConfig& c) {
    const auto* k = kernels::find(pass.kernel);
    if (!k) return internal("no kernel " + pass.kernel);
    const auto params = kernels::withDefaults(*k, c.params);
    // A pass that reads no image (the G-buffer's sphere trace) gives the same
    // outputs for the same kernel, parameters and sizes: a suite's many
    // configurations of one scene trace it once. Only its own parameters
    // (withDefaults) are in the key, so every AO setting shares it.
    static std::map<std::string, std::vector<HostImage>> sources;
    std::string key;
    if (pass.inputs.empty()) {
        char size[64];
        std::snprintf(size, sizeof size, " %dx%d%s", c.width, c.height, pass.half ? " half" : "");
        key = pass.kernel + size;
        for (const auto& [name, value] : params) {
            char v[40];
            std::snprintf(v, sizeof v, "=%.17g", value);
            key += " " + name + v;
        }
        if (auto hit = sources.find(key); hit != sources.end()) return hit->second;
    }
    std::vector<HostImage> inputs;
    for (const auto& in : pass.inputs) {
        if (in.source == ImageSource::Constant) {
            const auto* decl = kernels::findConstant(in.name);
            if (!decl) return internal("no constant " + in.name);
            const auto levels = decl->make(params);
            HostImage img(levels[0].width, levels[0].height, gpu::channelCount(decl->format));
            img.pixels = levels[0].pixels;
            inputs.push_back(std::move(img));
            continue;
        }
        CAVITY_ASSIGN(auto img, chain.read(in.name));
        inputs.push_back(std::move(img));
    }
    std::map<std::string, std::vector<float>> arrays;
    if (k->derive) k->derive(params, arrays);
    const int w = pass.half ? (c.width + 1) / 2 : c.width, h = pass.half ? (c.height + 1) / 2 : c.height;
    const auto frame = frameUniforms(w, h, c.width, c.height);
    reference::Context ctx{*k, params, arrays, frame, {}};
    for (const auto& i : inputs) ctx.inputs.push_back(&i);
    auto out = reference::run(ctx);
    if (out && !key.empty()) {
        if (sources.size() >= 8) sources.clear();   // a test's scenes and views; bounded
        sources[key] = *out;
    }
    return out;
}

// A checked chain and the configuration it ran, for a test that looks further.
struct CheckedChain {
    RunConfig config;
    std::unique_ptr<PassChain> chain;
};

// A case's size, kernel, resolution and stage; its scene and switches are
// the caller's to set (setParam).
RunConfig configOf(gpu::Api api, const Case& cs) {
    RunConfig c;
    c.api = api;
    c.width = cs.width;
    c.height = cs.height;
    c.kernel = cs.kernel;
    c.half = cs.half;
    c.stage = cs.stage;
    return c;
}

void checkChain(gpu::Backend& gpu, gpu::Api api, const Case& cs, CheckedChain* keep = nullptr) {
    RunConfig c = configOf(api, cs);
    ASSERT_TRUE(setParam(c, "scene", cs.scene).ok());
    if (cs.fusedTail) {
        ASSERT_TRUE(setParam(c, "fused_tail", "1").ok());
    }
    if (cs.interleave > 1) {
        ASSERT_TRUE(setParam(c, "interleave", std::to_string(cs.interleave)).ok());
    }
    if (cs.blur >= 0) {
        ASSERT_TRUE(setParam(c, "blur", std::to_string(cs.blur)).ok());
    }
    if (cs.samples > 0) {
        ASSERT_TRUE(setParam(c, "samples", std::to_string(cs.samples)).ok());
    }
    if (cs.steps > 0) {
        ASSERT_TRUE(setParam(c, "steps", std::to_string(cs.steps)).ok());
    }
    if (const auto* k = kernels::find(cs.kernel); cs.exact && k && kernels::declares(*k, "exact")) {
        ASSERT_TRUE(setParam(c, "exact", "1").ok());
    }
    auto chain = recordedChain(gpu, c);
    ASSERT_TRUE(chain) << chain.error().message;

    for (const auto& pass : (*chain)->passes()) {
        SCOPED_TRACE(configId(c) + " pass " + pass.name);
        const auto* k = kernels::find(pass.kernel);
        ASSERT_NE(k, nullptr);
        auto expected = referenceOf(**chain, pass, c);
        ASSERT_TRUE(expected) << expected.error().message;
        ASSERT_EQ(expected->size(), pass.outputs.size());
        for (size_t o = 0; o < pass.outputs.size(); ++o) {
            // 8-bit outputs may round either way on a value that sits on a step.
            Tolerance tol = toleranceFor(k->name);
            if (k->outputs[o].format == gpu::Format::RGBA8 || k->outputs[o].format == gpu::Format::R8)
                tol.maxAbs = std::max(tol.maxAbs, 1.0 / 255.0 + 1e-6);
            // The packed key (AO, linear depth, normal) in RGBA16F: a driver may round
            // the depth either way to half (lavapipe and the CPU differ on a
            // third of the pixels), one step of 2^-6 at depths 16-32. Its AO
            // channel is held to 1e-3 through the kernel's "ao" output and
            // the vertical blur's.
            if (k->outputs[o].name == "ao_key") tol.maxAbs = std::max(tol.maxAbs, 1.0 / 64.0 + 1e-6);
            auto got = (*chain)->read(pass.outputs[o]);
            ASSERT_TRUE(got) << got.error().message;
            HostImage want = (*expected)[o];
            quantize(want, k->outputs[o].format);
            const Diff d = diff(want, *got, tol.maxAbs);
            const double allowed = tol.outlierFraction * double(d.compared);
            EXPECT_LE(double(d.over), allowed)
                << pass.outputs[o] << ": " << d.over << " of " << d.compared << " pixels differ by more than "
                << tol.maxAbs << "; max " << d.maxAbs << " at (" << d.worstX << "," << d.worstY << "), mean "
                << d.meanAbs;
            if (tol.outlierFraction == 0) {
                EXPECT_LE(d.maxAbs, tol.maxAbs) << pass.outputs[o];
            }
        }
    }
    if (keep) *keep = {c, std::move(*chain)};
}

// Every AO pipeline, full and half resolution; the fragment stage too at 160x90.
void checkAll(gpu::Backend& gpu, gpu::Api api, const std::string& scene, int w, int h) {
    for (const auto& k : kernels::all()) {
        if (k.role != cavity::kernels::Role::Ao) continue;
        // A kernel package may come without a CPU reference: approvals gate
        // its images (docs/packages.md). ReferenceNames below holds that no
        // package forgot the line naming its own.
        if (!reference::hasReference(k.name)) continue;
        for (bool half : {false, true}) {
            if (half && !supportsHalf(k.name)) continue;
            for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
                if (stage == gpu::Stage::Fragment && w > 160) continue;
                checkChain(gpu, api, {scene, w, h, k.name, half, stage});
            }
        }
    }
}

TEST_P(KernelVsReference, Corner160x90) { checkAll(gpu(), api(), "corner", 160, 90); }
TEST_P(KernelVsReference, Corner320x180) { checkAll(gpu(), api(), "corner", 320, 180); }
TEST_P(KernelVsReference, Slats160x90) { checkAll(gpu(), api(), "slats", 160, 90); }
TEST_P(KernelVsReference, Slats320x180) { checkAll(gpu(), api(), "slats", 320, 180); }

// Images so thin that samples reach the pyramid's "tiny" levels, those
// whose level above is 1 texel across (include/pyramid.glsl,
// pyramidTexel), where a pick is undone a level at a time with its clamp:
// 3x256 reads levels past the 1-texel ones along its short side (a planted
// fault there, a texel off the image, fails it); 256x3 reads none of them.
TEST_P(KernelVsReference, ThinImagesReadTheTinyLevels) {
    for (const std::string kernel : {"alchemy_fast", "hemisphere_fast"})
        for (const auto& [w, h] : {std::pair{256, 3}, std::pair{3, 256}}) checkChain(gpu(), api(), {"corner", w, h, kernel});
}

// The fast kernels compile their sample count in and unroll the loop up to
// 64 samples (ssao_alchemy_fast.glsl); past that the count is the uniform's.
// Both sides of that limit, and an odd count, against the CPU reference.
// hemisphere_fast compiles its rays' shape in too (ssao_hemisphere_fast.glsl):
// n = 7 in rays of 4 ends in a shorter ray; 64 is 16 rays, two an iteration
// on GL; 15 in rays of 3 is an odd count of rays, one an iteration; 16 in
// rays of 3 ends in a ray of 1; 4 points in rays of 8 are one ray (steps
// over n); 16 in rays of 1 are 16 one-point rays; and 72 takes the shape
// from the table. ssdo_fast compiles its direction count and points a
// direction in (include/ssdo_fast.glsl), both passes alike: 7 directions of
// 3 points and of 1, and 72, past the limit, from the uniforms.
TEST_P(KernelVsReference, SampleCountsUnrolledAndNot) {
    for (const std::string kernel : {"alchemy_fast", "hemisphere_fast"})
        for (int n : {7, 64, 72}) {
            Case cs{"slats", 96, 54, kernel};
            cs.samples = n;
            checkChain(gpu(), api(), cs);
        }
    for (const auto& [n, steps] : {std::pair{15, 3}, std::pair{16, 3}, std::pair{4, 8}, std::pair{16, 1}}) {
        Case cs{"slats", 96, 54, "hemisphere_fast"};
        cs.samples = n;
        cs.steps = steps;
        checkChain(gpu(), api(), cs);
    }
    for (const auto& [n, steps] : {std::pair{7, 3}, std::pair{7, 1}, std::pair{72, 0}}) {
        Case cs{"slats", 96, 54, "ssdo_fast"};
        cs.samples = n;
        cs.steps = steps;
        checkChain(gpu(), api(), cs);
    }
}

// The separable blur's compute passes decode a workgroup's tile into shared
// memory when it fits in 768 texels, which every radius (1 to 32) does in
// the declared shapes, and read the texture otherwise
// (include/blur_separable.glsl): in 32x32 workgroups every radius
// overflows it. Both paths, the smallest and largest radius, at a size
// whose last workgroups hang over both edges, for the AO key alone and for
// SSDO's radiance beside it.
TEST_P(KernelVsReference, BlurRadiiTiledAndNot) {
    struct Env {
        ~Env() { unsetenv("CAVITY_WORKGROUP"); }
    } restore;
    for (const char* shape : {"", "32x32"}) {
        setenv("CAVITY_WORKGROUP", shape, 1);   // empty: each kernel's own
        for (const std::string kernel : {"alchemy_fast", "ssdo_fast"})
            for (int r : {1, 4, 32}) {
                Case cs{"slats", 100, 60, kernel};
                cs.blur = r;
                checkChain(gpu(), api(), cs);
            }
    }
}

// The other four scenes: the G-buffer march, one screen-space and one
// distance-field AO kernel, blur and composite, on both stages.
TEST_P(KernelVsReference, OtherScenes160x90) {
    for (const std::string scene : {"open", "contact", "grille", "plates"})
        for (const std::string kernel : {"alchemy", "sdf_hemisphere"})
            for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment})
                checkChain(gpu(), api(), {scene, 160, 90, kernel, false, stage});
}

// The depth pyramid's smaller levels, which the per-pass check above cannot
// see (a readback holds level 0): each must be the rotated-grid pick of the
// level above, bit for bit, at sizes that go odd (45, 11, 5 rows), and each
// texel's stored source pixel the one the reference finds by undoing the
// picks. A level that averaged, took the wrong texel of its block, stored
// the wrong source, or was never written (all zero) fails here. Both builds, one dispatch (the default:
// depth_pyramid_single, and at half resolution downsample_pyramid, which
// builds it from the depths it picks) and one per level (depth_pyramid
// after downsample_depth), and each level of the one bit for bit the
// other's; and at 37x21, where levels run down to 2x1 and the pick's clamp
// acts.
TEST_P(KernelVsReference, DepthPyramidLevels) {
    for (auto [w, h] : {std::pair{160, 90}, std::pair{37, 21}})
        for (bool half : {false, true}) {
            std::vector<HostImage> built[2];
            for (int perLevel = 0; perLevel < 2; ++perLevel) {
                RunConfig c;
                c.api = api();
                c.width = w;
                c.height = h;
                c.kernel = "alchemy_fast";
                c.half = half;
                ASSERT_TRUE(setParam(c, "scene", "slats").ok());
                ASSERT_TRUE(setParam(c, "pyramid_per_level", perLevel ? "1" : "0").ok());
                auto chain = recordedChain(gpu(), c);
                ASSERT_TRUE(chain) << chain.error().message;
                // At half resolution the downsample builds the one-dispatch
                // pyramid from the depths it picks.
                const std::string builder =
                    perLevel ? "depth_pyramid" : (half ? "downsample_pyramid" : "depth_pyramid_single");
                EXPECT_TRUE(std::any_of((*chain)->passes().begin(), (*chain)->passes().end(),
                                        [&](const auto& pass) { return pass.kernel == builder; }))
                    << configId(c) << " builds no " << builder;
                const std::string image = half ? "zmip_half" : "zmip";
                auto level0 = (*chain)->read(image);
                ASSERT_TRUE(level0) << level0.error().message;
                const auto* decl = kernels::find(builder);
                ASSERT_NE(decl, nullptr);
                const auto zmip = std::find_if(decl->outputs.begin(), decl->outputs.end(),
                                               [](const kernels::OutputDecl& o) { return o.name == "zmip"; });
                ASSERT_NE(zmip, decl->outputs.end()) << builder;
                const int levels = zmip->mipLevels;
                ASSERT_GT(levels, 2);
                const auto want = reference::pyramidLevels(*level0, levels);
                // Level 0 holds each pixel's depth beside the pixel itself.
                EXPECT_EQ(level0->pixels, want[0].pixels) << builder << " level 0";
                built[perLevel].push_back(*level0);
                for (int l = 1; l < levels; ++l) {
                    SCOPED_TRACE(builder + " " + std::to_string(w) + "x" + std::to_string(h) + " " + image + " level " +
                                 std::to_string(l));
                    auto got = (*chain)->read(image, l);
                    ASSERT_TRUE(got) << got.error().message;
                    ASSERT_EQ(got->width, want[size_t(l)].width);
                    ASSERT_EQ(got->height, want[size_t(l)].height);
                    EXPECT_EQ(got->pixels, want[size_t(l)].pixels);
                    // (A 1x1 level of the tiny image may pick the sky.)
                    long long surface = 0;
                    for (int y = 0; y < got->height; ++y)
                        for (int x = 0; x < got->width; ++x) surface += got->at(x, y) > 0;
                    if (got->pixels.size() >= 16) {
                        EXPECT_GT(surface, 0) << "no surface depth at all";
                    }
                    built[perLevel].push_back(std::move(*got));
                }
            }
            ASSERT_EQ(built[0].size(), built[1].size());
            for (size_t l = 0; l < built[0].size(); ++l)
                EXPECT_EQ(built[0][l].pixels, built[1][l].pixels) << "level " << l << " differs between the two builds";
        }
}

// The fused half-resolution tail (upsample_composite) against the two passes
// it replaces: its own CPU reference per pass, as every kernel's, and then
// the images the user and the gate see. The full-resolution AO is bit for
// bit upsample_bilateral's; the colour is within one 8-bit step of
// upsample_bilateral followed by composite (the fused pass composites the
// AO before the R16F store rounds it: on lavapipe a few pixels in a hundred
// move a step). Both stages, both scenes, the separable and the bilateral tails.
TEST_P(KernelVsReference, FusedTailMakesTheImagesOfUpsampleThenComposite) {
    for (const std::string scene : {"corner", "slats"})
        for (const std::string kernel : {"alchemy", "alchemy_fast", "hemisphere_fast"})
            for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
                checkChain(gpu(), api(), {scene, 160, 90, kernel, true, stage, true});
                std::map<std::string, HostImage> images[2];
                for (int fused = 0; fused < 2; ++fused) {
                    RunConfig c = configOf(api(), {scene, 160, 90, kernel, true, stage});
                    ASSERT_TRUE(setParam(c, "scene", scene).ok());
                    ASSERT_TRUE(setParam(c, "fused_tail", fused ? "1" : "0").ok());
                    auto chain = recordedChain(gpu(), c);
                    ASSERT_TRUE(chain) << chain.error().message;
                    bool hasFusedPass = false;
                    for (const auto& pass : (*chain)->passes()) hasFusedPass |= pass.kernel == "upsample_composite";
                    EXPECT_EQ(hasFusedPass, fused == 1) << configId(c);
                    for (const std::string image : {"ao_blur", "color"}) {
                        auto got = (*chain)->read(image);
                        ASSERT_TRUE(got) << got.error().message;
                        images[fused].emplace(image, std::move(*got));
                    }
                }
                const Diff ao = diff(images[0].at("ao_blur"), images[1].at("ao_blur"), 0.0);
                EXPECT_EQ(ao.over, 0) << scene << " " << kernel << " ao_blur: max " << ao.maxAbs << " at ("
                                      << ao.worstX << "," << ao.worstY << ")";
                const Diff color = diff(images[0].at("color"), images[1].at("color"), 1.0 / 255.0 + 1e-6);
                EXPECT_EQ(color.over, 0) << scene << " " << kernel << " color: max " << color.maxAbs << " at ("
                                         << color.worstX << "," << color.worstY << ")";
                // Only rounding: a step on a few pixels, not a shifted image.
                EXPECT_LT(color.meanAbs, 0.25 / 255.0) << scene << " " << kernel;
            }
}

// Interleaved layers (KernelDecl::interleaved): the AO pass dispatched as
// k x k layers over the depth split into them, against the CPU reference,
// which shades the same pixels with the same phases in a plain loop over
// the image: every pass, the pyramid's atlas of layers included, as closely
// as the plain dispatch is held. Sizes that divide into the layers and
// sizes that do not (the atlas's padding), full and half resolution, and
// the fragment stage, whose interleaved pass runs as compute. k = 3 at 160
// px: an atlas two texels wider than the image, which a dispatch over the
// image's own width (in workgroups of 8 or 16) left unshaded, a black
// column the coverage check's gpu-cpu group showed.
TEST_P(KernelVsReference, InterleavedLayersShadeAsThePlainReferenceDoes) {
    for (const std::string kernel : {"alchemy_fast", "hemisphere_fast"})
        for (int k : {2, 3, 4})
            for (auto [w, h] : {std::pair{160, 90}, std::pair{37, 21}})
                for (bool half : {false, true}) {
                    const std::string scene = (w + k) % 2 ? "corner" : "slats";
                    const auto stage = half && k == 4 ? gpu::Stage::Fragment : gpu::Stage::Compute;
                    CheckedChain checked;
                    checkChain(gpu(), api(), {scene, w, h, kernel, half, stage, false, k}, &checked);
                    if (HasFatalFailure()) return;
                    const RunConfig& c = checked.config;
                    bool layered = false;
                    for (const auto& pass : checked.chain->passes()) layered |= pass.kernel == "depth_pyramid_layered";
                    EXPECT_TRUE(layered) << configId(c) << ": no pass splits the depth into layers";
                    // The layers' phases reached the shader, and the atlas is whole layers.
                    const auto* decl = kernels::find(kernel);
                    auto src = kernels::assemble(*decl, gpu::Stage::Compute, {}, &c.params);
                    ASSERT_TRUE(src) << src.error().message;
                    EXPECT_NE(src->glsl.find("#define CAVITY_INTERLEAVE " + std::to_string(k)), std::string::npos);
                    auto atlas = checked.chain->read(half ? "zlayers_half" : "zlayers");
                    ASSERT_TRUE(atlas) << atlas.error().message;
                    const int pw = half ? (w + 1) / 2 : w, ph = half ? (h + 1) / 2 : h;
                    EXPECT_EQ(atlas->width, (pw + k - 1) / k * k);
                    EXPECT_EQ(atlas->height, (ph + k - 1) / k * k);
                }
}

// The dispatch shape itself: with the AO kernel's body replaced by one that
// stores its workgroup's id, every pixel shows which workgroup shaded it.
// Plain, that is pixel / the workgroup's size; interleaved, the workgroup
// over the layers laid side by side, (pixel mod k) * layerSize + pixel / k,
// over the size: a workgroup's pixels are every k-th pixel of one layer. (The images alone
// cannot tell: which invocation shades a pixel does not change its value.)
TEST_P(KernelVsReference, InterleavedPassShadesEachLayerInItsOwnWorkgroups) {
    const std::map<std::string, std::string> workgroupIds = {
        {"ao/alchemy_fast/ssao_alchemy_fast.glsl",
         "#include \"include/common.glsl\"\n"
         "void cavity_main(ivec2 pixel) {\n"
         "    write_ao(pixel, vec4(float(gl_WorkGroupID.x), 0.0, 0.0, 0.0));\n"
         "    write_ao_key(pixel, vec4(float(gl_WorkGroupID.y), 0.0, 0.0, 0.0));\n"
         "}\n"}};
    for (int k : {1, 4}) {
        RunConfig c;
        c.api = api();
        c.width = 160;
        c.height = 90;
        c.kernel = "alchemy_fast";
        ASSERT_TRUE(setParam(c, "interleave", std::to_string(k)).ok());
        auto chain = PassChain::create(gpu(), c, workgroupIds);
        ASSERT_TRUE(chain) << chain.error().message;
        gpu().beginFrame();
        (*chain)->record();
        ASSERT_TRUE(gpu().endFrame().ok());
        auto x = (*chain)->read("ao"), y = (*chain)->read("ao_key");
        ASSERT_TRUE(x && y);
        const int lw = (c.width + k - 1) / k, lh = (c.height + k - 1) / k;
        const auto wg = kernels::workgroupSize(*kernels::find("alchemy_fast"));
        ASSERT_TRUE(wg);
        const int gx = int(wg->x), gy = int(wg->y);
        int wrong = 0;
        for (int py = 0; py < c.height; ++py)
            for (int px = 0; px < c.width; ++px) {
                const int ax = px % k * lw + px / k, ay = py % k * lh + py / k;
                wrong += x->at(px, py, 0) != float(ax / gx) || y->at(px, py, 0) != float(ay / gy);
            }
        EXPECT_EQ(wrong, 0) << "interleave " << k << ": pixels shaded by another workgroup than the layers' own";
    }
}

// The precision contract: a fast kernel as it ships, with its default
// --exact 0 (the GPU's own division, inverse square root and sine, fma
// contraction allowed), against its exact CPU reference. A rounding
// difference may move a sample across a texel edge or the radius and change
// that pixel's AO by about a sample's share, so the bound is on how many
// pixels move at all and on the mean, not on the worst pixel. Measured on
// llvmpipe and lavapipe at 320x180, full and half, both stages: a single
// pixel at most over 1e-3 (one half-resolution pixel of hemisphere_fast on
// slats, one ray of four flipped), and a small mean. The bound
// (kInexactTolerance) leaves room for a GPU, whose sine Vulkan lets be
// 2^-11 off, which moves a far sample by a tenth of a pixel; its mean of 5e-4
// is an eighth of an 8-bit step. The CPU renderers, which CI runs, are held near
// what they measured (1e-4 of the pixels, 1.4x the worst share; 2e-4, 1.4x
// the worst mean), so that the test still sees a change for the worse
// there; the contract's bound is for a GPU.
// Every other pass of these pipelines, and the AO pass with --exact 1, is
// held to every pixel by the tests above.
struct InexactTolerance {
    double overShare;   // share of pixels more than 1e-3 off
    double meanAbs;     // mean |difference| over the image
};
const InexactTolerance kInexactTolerance{0.01, 5e-4};
const InexactTolerance kInexactOnCpuRenderers{1e-4, 2e-4};

// Channel 0 of an image: the AO of the packed key.
HostImage firstChannel(const HostImage& image) {
    HostImage out(image.width, image.height, 1);
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = image.pixels[i * size_t(image.channels)];
    return out;
}

// The AO pass of `c`'s chain, run with the kernel's default arithmetic,
// against its CPU reference under the contract's bound.
void checkInexactAo(gpu::Backend& gpu, const RunConfig& c) {
    SCOPED_TRACE(configId(c));
    auto chain = recordedChain(gpu, c);
    ASSERT_TRUE(chain) << chain.error().message;
    const auto& passes = (*chain)->passes();
    const auto ao = std::find_if(passes.begin(), passes.end(), [](const auto& p) { return p.name == "ao"; });
    ASSERT_NE(ao, passes.end());
    const auto* k = kernels::find(ao->kernel);
    // The default reached the shader: the hardware's own arithmetic.
    auto src = kernels::assemble(*k, c.stage, {}, &c.params);
    ASSERT_TRUE(src) << src.error().message;
    EXPECT_NE(src->glsl.find("#define CAVITY_INEXACT 1"), std::string::npos);
    auto expected = referenceOf(**chain, *ao, c);
    ASSERT_TRUE(expected) << expected.error().message;
    for (size_t o = 0; o < ao->outputs.size(); ++o) {
        HostImage want = (*expected)[o];
        quantize(want, k->outputs[o].format);
        auto got = (*chain)->read(ao->outputs[o]);
        ASSERT_TRUE(got) << got.error().message;
        // The packed key's AO channel; its depth and normal are exact either way.
        const Diff d = diff(firstChannel(want), firstChannel(*got), 1e-3);
        const double share = double(d.over) / double(d.compared);
        std::printf("[ inexact  ] %s %s: %.4f%% of pixels over 1e-3, max %.4f, mean %.2e\n", configId(c).c_str(),
                    ao->outputs[o].c_str(), 100 * share, d.maxAbs, d.meanAbs);
        const auto& bound = gpu.info().softwareRenderer ? kInexactOnCpuRenderers : kInexactTolerance;
        EXPECT_LE(share, bound.overShare) << ao->outputs[o];
        EXPECT_LE(d.meanAbs, bound.meanAbs) << ao->outputs[o];
    }
}

TEST_P(KernelVsReference, DefaultFastKernelsHoldTheStatedTolerance) {
    for (const std::string scene : {"corner", "slats"})
        for (const std::string kernel : {"alchemy_fast", "hemisphere_fast"})
            for (bool half : {false, true})
                for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
                    RunConfig c = configOf(api(), {scene, 320, 180, kernel, half, stage});
                    ASSERT_TRUE(setParam(c, "scene", scene).ok());
                    checkInexactAo(gpu(), c);
                }
}

CAVITY_ALL_BACKENDS(KernelVsReference);

// OpenGL against Vulkan on the same SPIR-V. Mesa compiles the two SPIR-V
// flavours (GL 4.5 and Vulkan 1.2 targets) separately, so a handful of
// pixels round differently: measured on llvmpipe/lavapipe, at most one
// storage step (a half-float ulp, 4.9e-4 below 1.0) on a few pixels,
// and 32-bit positions within the ray march's own hit tolerance (it stops
// once the distance is under 1e-4 t, so two compilations may stop a step
// apart: 3.2e-4 world units seen). The bound: every pixel within one storage
// step (3e-4 relative for positions, one 8-bit step for the dithered
// composite) and a mean difference of at most 1e-5.
TEST(ApiAgreement, GlAndVkProduceTheSameImages) {
    std::string why;
    gpu::Backend* gl = sharedBackend(gpu::Api::OpenGL, &why);
    gpu::Backend* vk = gl ? sharedBackend(gpu::Api::Vulkan, &why) : nullptr;
    if (!gl || !vk) {
        if (inCI()) FAIL() << "CI=true requires both backends: " << why;
        GTEST_SKIP() << why;
    }
    for (const std::string scene : {"corner", "slats"}) {
        std::map<std::string, HostImage> images[2];
        int which = 0;
        for (auto* g : {gl, vk}) {
            RunConfig c;
            c.api = g->api();
            ASSERT_TRUE(setParam(c, "scene", scene).ok());
            auto chain = recordedChain(*g, c);
            ASSERT_TRUE(chain) << chain.error().message;
            for (const std::string name : {"position", "normal", "ao", "ao_blur", "color"}) {
                auto img = (*chain)->read(name);
                ASSERT_TRUE(img) << img.error().message;
                images[which][name] = std::move(*img);
            }
            ++which;
        }
        for (const auto& [name, a] : images[0]) {
            const HostImage& b = images[1][name];
            ASSERT_TRUE(a.sameShape(b));
            double worst = 0, sum = 0;
            size_t over = 0;
            for (size_t i = 0; i < a.pixels.size(); ++i) {
                const double d = std::fabs(double(a.pixels[i]) - double(b.pixels[i]));
                const double mag = std::max(1.0, double(std::fabs(a.pixels[i])));
                const double step = name == "color" ? 1.0 / 255.0 + 1e-6
                                  : name == "position" ? 3e-4 * mag   // the march stops within 1e-4 t
                                                       : std::ldexp(1.0, -11) * mag;   // one half ulp at |v| <= 1
                over += d > step;
                worst = std::max(worst, d);
                sum += d;
            }
            const double mean = sum / double(a.pixels.size());
            EXPECT_EQ(over, 0u) << scene << " " << name << ": max difference " << worst;
            EXPECT_LE(mean, 1e-5) << scene << " " << name;
            std::printf("%s %s: GL vs VK max %.3g, mean %.3g\n", scene.c_str(), name.c_str(), worst, mean);
        }
    }
}

// BackendOptions::fullBarriers widens every barrier() and nothing else, so
// each image of every fast pipeline (full and half resolution, SSDO) and of
// the seed's comes out bit for bit as with the narrow barriers; its
// validation-layer run reports nothing either.
TEST_P(KernelVsReference, FullBarriersChangeNoImage) {
    gpu::BackendOptions o;
    o.validation = true;
    o.fullBarriers = true;
    auto full = gpu::createBackend(api(), o);
    ASSERT_TRUE(full) << full.error().message;
    for (const std::string kernel : {"alchemy", "alchemy_fast", "hemisphere_fast", "ssdo_fast"}) {
        for (bool half : {false, true}) {
            if (half && !supportsHalf(kernel)) continue;
            const RunConfig c = smallConfig(api(), kernel, half);
            auto narrow = frameImages(gpu(), c), wide = frameImages(**full, c);
            ASSERT_TRUE(narrow && wide) << (narrow ? wide.error() : narrow.error()).message;
            for (const auto& [name, image] : *narrow)
                EXPECT_EQ(image.pixels, wide->at(name).pixels) << configId(c) << " " << name;
        }
    }
    const auto messages = (*full)->takeDebugMessages();
    EXPECT_TRUE(messages.empty()) << messages.front();
}

// CAVITY_WORKGROUP reshapes every compute dispatch and nothing else: each
// invocation shades its own pixel, so every image of the fast pipelines (the
// interleaved layers included, whose workgroups then span other pixels of
// one layer) comes out bit for bit as with the default. A shape the variable cannot
// take is an error naming it.
TEST_P(KernelVsReference, WorkgroupShapeChangesNoImage) {
    struct Env {
        ~Env() { unsetenv("CAVITY_WORKGROUP"); }
    } restore;
    for (const std::string kernel : {"alchemy_fast", "hemisphere_fast", "ssdo_fast"}) {
        for (int variant = 0; variant < 3; ++variant) {
            RunConfig c = smallConfig(api(), kernel, variant == 1 && supportsHalf(kernel));
            if (variant == 2 && kernel != "ssdo_fast") {
                ASSERT_TRUE(setParam(c, "interleave", "4").ok());
            }
            unsetenv("CAVITY_WORKGROUP");
            auto declared = frameImages(gpu(), c);
            setenv("CAVITY_WORKGROUP", "32x4", 1);
            auto reshaped = frameImages(gpu(), c);
            ASSERT_TRUE(declared && reshaped) << (declared ? reshaped.error() : declared.error()).message;
            for (const auto& [name, image] : *declared)
                EXPECT_EQ(image.pixels, reshaped->at(name).pixels) << configId(c) << " " << name;
        }
    }
    for (const char* bad : {"16", "3x16", "64x64", "4x4", "8x8x1", "-8x8"}) {
        setenv("CAVITY_WORKGROUP", bad, 1);
        const auto wg = kernels::workgroupSize(*kernels::find("alchemy_fast"));
        ASSERT_FALSE(wg) << bad;
        EXPECT_NE(wg.error().message.find(std::string("CAVITY_WORKGROUP=") + bad + ": must be WxH"), std::string::npos)
            << wg.error().message;
    }
}

}  // namespace
}  // namespace cavity::test

namespace cavity::test {
namespace {

// The rasterised G-buffer (meshes from harness/pipeline/meshes.cpp, hardware depth)
// against the ray-marched one of the same scene: the same surfaces, so the
// same positions and normals away from silhouettes. Bounds, and why: the
// sphere's 96x48 tessellation is within 3e-4 of its radius, the march stops
// within 1e-4 t; a pixel whose centre straddles a silhouette may hit in one
// and miss in the other (on at most a hundredth of the pixels); positions
// within 2e-3 of the linear depth (over the cosine of the incidence angle)
// on all but a hundredth of the pixels both hit; normals within 2.6 degrees. All six scenes.
class RasterGBuffer : public GpuTest {};

TEST_P(RasterGBuffer, MatchesTheRayMarchedGBuffer) {
    for (const std::string scene : {"corner", "slats", "open", "contact", "grille", "plates"}) {
        std::map<bool, std::map<std::string, HostImage>> img;
        for (bool raster : {false, true}) {
            RunConfig c;
            c.api = api();
            c.raster = raster;
            ASSERT_TRUE(setParam(c, "scene", scene).ok());
            auto images = renderImages(gpu(), c, {"position", "normal", "ao_blur"});
            ASSERT_TRUE(images) << images.error().message;
            img[raster] = std::move(*images);
        }
        const auto& ps = img[false]["position"];
        const auto& pr = img[true]["position"];
        long long both = 0, mismatch = 0, farPos = 0, farNormal = 0;
        double aoDiff = 0;
        for (int y = 0; y < ps.height; ++y)
            for (int x = 0; x < ps.width; ++x) {
                const float ds = ps.at(x, y, 3), dr = pr.at(x, y, 3);
                if ((ds > 0) != (dr > 0)) ++mismatch;
                if (ds <= 0 || dr <= 0) continue;
                ++both;
                double d2 = 0, ndot = 0, nv = 0, pp = 0;
                for (int k = 0; k < 3; ++k) {
                    d2 += std::pow(ps.at(x, y, k) - pr.at(x, y, k), 2.0);
                    ndot += img[false]["normal"].at(x, y, k) * img[true]["normal"].at(x, y, k);
                    nv += img[false]["normal"].at(x, y, k) * ps.at(x, y, k);
                    pp += double(ps.at(x, y, k)) * ps.at(x, y, k);
                }
                // The march stops within 1e-4 t of the surface, which is
                // 1e-4 t / cos(incidence) along the ray: at the grazing far
                // floor of `open` that is over 2e-3 t.
                const double cosIncidence = std::max(std::fabs(nv) / std::sqrt(pp), 0.05);
                farPos += std::sqrt(d2) > 2e-3 * ds / cosIncidence;
                farNormal += ndot < 0.999;
                aoDiff += std::fabs(img[false]["ao_blur"].at(x, y) - img[true]["ao_blur"].at(x, y));
            }
        const double pixels = double(ps.width) * ps.height;
        EXPECT_LE(mismatch, 0.01 * pixels) << scene << ": hit in one G-buffer only";
        EXPECT_LE(farPos, 0.01 * double(both)) << scene << ": positions apart";
        EXPECT_LE(farNormal, 0.02 * double(both)) << scene << ": normals apart";
        EXPECT_LT(aoDiff / double(both), 0.01) << scene << ": mean blurred-AO difference";
        std::printf("%s raster vs sdf: %lld silhouette mismatches, %lld far positions, %lld far normals of %lld; mean |dAO| %.4f\n",
                    scene.c_str(), mismatch, farPos, farNormal, both, aoDiff / double(both));
    }
}

CAVITY_ALL_BACKENDS(RasterGBuffer);

}  // namespace
}  // namespace cavity::test

namespace cavity::test {
namespace {

// The stage contract: "compute and fragment results agree to 1e-5 or tighter". The two
// entry points wrap one body (kernels/assemble.cpp), so every image of every
// pipeline, G-buffer to composite, is compared between the stages: floats
// within 1e-5, the 8-bit composite exactly. Both resolutions' pipelines, on
// corner (every AO kernel and the ground truth) and contact.
class StageAgreement : public GpuTest {};

TEST_P(StageAgreement, ComputeAndFragmentAgree) {
    double largest = 0;
    std::vector<std::string> names{"ground_truth"};
    for (const auto& k : kernels::all())
        if (k.role == cavity::kernels::Role::Ao) names.push_back(k.name);
    for (const std::string scene : {"corner", "contact"})
        for (const auto& name : names)
            for (bool half : {false, true}) {
                if (half && (!supportsHalf(name) || name == "ground_truth")) continue;
                std::map<gpu::Stage, std::map<std::string, HostImage>> img;
                std::vector<std::string> images;
                for (auto stage : {gpu::Stage::Compute, gpu::Stage::Fragment}) {
                    RunConfig c;
                    c.api = api();
                    c.kernel = name;
                    c.width = 96;
                    c.height = 54;
                    c.half = half;
                    c.stage = stage;
                    ASSERT_TRUE(setParam(c, "scene", scene).ok());
                    images.clear();
                    for (const auto& p : buildPasses(c)) images.insert(images.end(), p.outputs.begin(), p.outputs.end());
                    auto read = renderImages(gpu(), c, images);
                    ASSERT_TRUE(read) << read.error().message;
                    img[stage] = std::move(*read);
                }
                for (const auto& o : images) {
                    const HostImage& a = img[gpu::Stage::Compute][o];
                    const HostImage& b = img[gpu::Stage::Fragment][o];
                    ASSERT_TRUE(a.sameShape(b)) << name << " " << o;
                    double worst = 0;
                    for (size_t i = 0; i < a.pixels.size(); ++i)
                        worst = std::max(worst, std::fabs(double(a.pixels[i]) - double(b.pixels[i])));
                    EXPECT_LE(worst, 1e-5) << scene << " " << name << (half ? " half " : " full ") << o;
                    largest = std::max(largest, worst);
                }
            }
    std::printf("largest compute/fragment difference over every image: %.3g\n", largest);
}

CAVITY_ALL_BACKENDS(StageAgreement);

}  // namespace
// Each package names its CPU reference with one line (`reference = "..."`):
// a reference registered under a kernel's own name that its package does
// not name is a line forgotten, and one that no kernel names is dead code,
// and a name no reference has is a typo.
TEST(ReferenceNames, EveryRegisteredReferenceIsNamedByItsKernelsPackage) {
    std::set<std::string> named;
    for (const auto& k : kernels::all()) {
        if (k.reference.empty()) {
            EXPECT_FALSE(reference::isReference(k.name)) << k.name << ": its package does not name its CPU reference";
            continue;
        }
        EXPECT_TRUE(reference::isReference(k.reference)) << k.name << ": reference = " << k.reference;
        named.insert(k.reference);
    }
    for (const auto& r : reference::referenceNames()) EXPECT_TRUE(named.count(r)) << r << ": no kernel names it";
    EXPECT_GE(named.size(), 30u);
}

}  // namespace cavity::test
