// Backend conformance: the contract of backends/backend.h, one body per API.
#include "gpu_fixture.h"
#include "pipeline/kernel_runner.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>

namespace cavity::test {
namespace {

class Backend : public GpuTest {};

gpu::ShaderSource compute(const std::string& body) {
    return {"conformance", gpu::Stage::Compute,
            "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n" + body, {"<conformance>"}};
}

TEST_P(Backend, ReportsDevice) {
    const auto& info = gpu().info();
    EXPECT_EQ(info.api, gpu::apiName(api()));
    EXPECT_FALSE(info.deviceName.empty());
    EXPECT_FALSE(info.apiVersion.empty());
}

TEST_P(Backend, UploadReadbackRoundTripsEveryFormat) {
    for (auto f : {gpu::Format::R8, gpu::Format::R16F, gpu::Format::R32F, gpu::Format::RG16F, gpu::Format::RG32F,
                   gpu::Format::RGBA8, gpu::Format::RGBA16F, gpu::Format::RGBA32F, gpu::Format::D32}) {
        const int w = 13, h = 7, c = gpu::channelCount(f);
        HostImage src(w, h, c);
        for (size_t i = 0; i < src.pixels.size(); ++i) src.pixels[i] = float((i * 37) % 101) / 100.0f;
        auto img = gpu().createImage({w, h, f, 1, "roundtrip"});
        ASSERT_TRUE(img) << img.error().message;
        ASSERT_TRUE(gpu().uploadImage(*img, 0, src.pixels).ok()) << gpu::formatName(f);
        auto back = gpu().readImage(*img);
        ASSERT_TRUE(back) << back.error().message;
        HostImage expect = src;
        quantize(expect, f);
        HostImage got(w, h, c);
        got.pixels = *back;
        EXPECT_LE(diff(expect, got).maxAbs, 1e-7) << gpu::formatName(f);
        gpu().destroy(*img);
    }
}

TEST_P(Backend, ComputeWritesEveryPixelOnceInRowMajorOrder) {
    const int w = 37, h = 19;
    auto out = gpu().createImage({w, h, gpu::Format::RGBA32F, 1, "out"});
    ASSERT_TRUE(out);
    gpu::ComputePipelineDesc d;
    d.shader = compute(
        "layout(binding = 0, rgba32f) uniform writeonly image2D o;\n"
        "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
        "  if (p.x < 37 && p.y < 19) imageStore(o, p, vec4(p.x, p.y, p.x + 100 * p.y, 1)); }\n");
    d.layout = {{0, gpu::BindingKind::StorageImage, gpu::Format::RGBA32F}};
    auto pipe = gpu().createComputePipeline(d);
    ASSERT_TRUE(pipe) << pipe.error().message;
    gpu::Bind b{0, *out, {}, {}};
    gpu().beginFrame();
    gpu().dispatch(*pipe, std::span(&b, 1), 5, 3);
    ASSERT_TRUE(gpu().endFrame().ok());
    auto px = gpu().readImage(*out);
    ASSERT_TRUE(px);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = &(*px)[(size_t(y) * w + x) * 4];
            ASSERT_EQ(p[0], float(x));
            ASSERT_EQ(p[1], float(y));
        }
    gpu().destroy(*pipe);
    gpu().destroy(*out);
}

TEST_P(Backend, FragmentRowZeroIsFirstRowAndMrtWritesBoth) {
    const int w = 16, h = 9;
    auto a = gpu().createImage({w, h, gpu::Format::R32F, 1, "a"});
    auto b = gpu().createImage({w, h, gpu::Format::RGBA8, 1, "b"});
    ASSERT_TRUE(a && b);
    gpu::GraphicsPipelineDesc d;
    d.vertex = {"fs", gpu::Stage::Vertex,
                "#version 450\nvoid main() {\n#ifdef VULKAN\n int id = gl_VertexIndex;\n#else\n int id = gl_VertexID;\n#endif\n"
                " vec2 p = vec2((id << 1) & 2, id & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n",
                {"<vs>"}};
    d.fragment = {"fs", gpu::Stage::Fragment,
                  "#version 450\nlayout(location = 0) out vec4 o0; layout(location = 1) out vec4 o1;\n"
                  "void main() { o0 = vec4(gl_FragCoord.y); o1 = vec4(0.25, 0.5, 0.75, 1.0); }\n",
                  {"<fs>"}};
    d.colorFormats = {gpu::Format::R32F, gpu::Format::RGBA8};
    auto pipe = gpu().createGraphicsPipeline(d);
    ASSERT_TRUE(pipe) << pipe.error().message;
    gpu::RenderTargets t;
    t.colors = {*a, *b};
    gpu().beginFrame();
    gpu().draw(*pipe, {}, t, 3);
    ASSERT_TRUE(gpu().endFrame().ok());
    auto pa = gpu().readImage(*a);
    auto pb = gpu().readImage(*b);
    ASSERT_TRUE(pa && pb);
    for (int y = 0; y < h; ++y) EXPECT_EQ((*pa)[size_t(y) * w], float(y) + 0.5f) << "row " << y;
    EXPECT_NEAR((*pb)[1], 0.5f, 1.0f / 255.0f);
    gpu().destroy(*pipe);
    gpu().destroy(*a);
    gpu().destroy(*b);
}

// Each level holds 100 / its width, so a store to the wrong level shows.
gpu::ComputePipelineDesc levelMarker() {
    gpu::ComputePipelineDesc d;
    d.shader = compute(
        "layout(binding = 0, r32f) uniform writeonly image2D o;\n"
        "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
        "  if (all(lessThan(p, imageSize(o)))) imageStore(o, p, vec4(100.0 / float(imageSize(o).x))); }\n");
    d.layout = {{0, gpu::BindingKind::StorageImage, gpu::Format::R32F}};
    return d;
}

TEST_P(Backend, StorageImageWritesTheBoundMipLevel) {
    auto img = gpu().createImage({8, 8, gpu::Format::R32F, 3, "levels"});
    ASSERT_TRUE(img) << img.error().message;
    ASSERT_TRUE(gpu().uploadImage(*img, 0, std::vector<float>(64, 7.0f)).ok());
    auto pipe = gpu().createComputePipeline(levelMarker());
    ASSERT_TRUE(pipe) << pipe.error().message;
    gpu::Bind level1{0, *img, {}, {}, 1}, level2{0, *img, {}, {}, 2};
    gpu().beginFrame();
    gpu().dispatch(*pipe, std::span(&level1, 1), 1, 1);
    gpu().dispatch(*pipe, std::span(&level2, 1), 1, 1);
    ASSERT_TRUE(gpu().endFrame().ok());
    const float expect[3] = {7.0f, 25.0f, 50.0f};   // level 0 as uploaded; 100/4, 100/2
    for (int l = 0; l < 3; ++l) {
        auto px = gpu().readImage(*img, l);
        ASSERT_TRUE(px) << px.error().message;
        ASSERT_EQ(px->size(), size_t(64 >> (2 * l)));
        for (float v : *px) ASSERT_EQ(v, expect[l]) << "level " << l;
    }

    gpu::Bind level3{0, *img, {}, {}, 3};
    gpu().beginFrame();
    gpu().dispatch(*pipe, std::span(&level3, 1), 1, 1);
    const Status s = gpu().endFrame();
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("no mip level 3 (it has 3)"), std::string::npos) << s.error().message;
    gpu().destroy(*pipe);
    gpu().destroy(*img);
}

// How a depth pyramid is built: each pass texelFetches level k-1 of the image
// through a sampled binding (every level) and stores level k of the same image.
TEST_P(Backend, PassReadsLevelBelowWhileWritingNextLevelOfOneImage) {
    auto img = gpu().createImage({8, 8, gpu::Format::R32F, 3, "pyramid"});
    ASSERT_TRUE(img) << img.error().message;
    std::vector<float> base(64);
    for (int i = 0; i < 64; ++i) base[size_t(i)] = float(i);   // x + 8y
    ASSERT_TRUE(gpu().uploadImage(*img, 0, base).ok());
    gpu::ComputePipelineDesc d;
    d.shader = compute(
        "layout(binding = 0) uniform sampler2D src;\n"
        "layout(binding = 1, r32f) uniform writeonly image2D dst;\n"
        "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
        "  if (any(greaterThanEqual(p, imageSize(dst)))) return;\n"
        "  int lod = findMSB(textureSize(src, 0).x / imageSize(dst).x) - 1;\n"
        "  float m = 0.0;\n"
        "  for (int i = 0; i < 4; ++i) m = max(m, texelFetch(src, 2 * p + ivec2(i & 1, i >> 1), lod).r);\n"
        "  imageStore(dst, p, vec4(m)); }\n");
    d.layout = {{0, gpu::BindingKind::SampledImage, {}}, {1, gpu::BindingKind::StorageImage, gpu::Format::R32F}};
    auto pipe = gpu().createComputePipeline(d);
    ASSERT_TRUE(pipe) << pipe.error().message;
    const gpu::Bind to1[2] = {{0, *img, {}, {}}, {1, *img, {}, {}, 1}};
    const gpu::Bind to2[2] = {{0, *img, {}, {}}, {1, *img, {}, {}, 2}};
    gpu().beginFrame();
    gpu().dispatch(*pipe, to1, 1, 1);
    gpu().barrier();
    gpu().dispatch(*pipe, to2, 1, 1);
    ASSERT_TRUE(gpu().endFrame().ok());
    auto l1 = gpu().readImage(*img, 1);
    auto l2 = gpu().readImage(*img, 2);
    ASSERT_TRUE(l1 && l2);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) ASSERT_EQ((*l1)[size_t(y * 4 + x)], float(2 * x + 1 + 8 * (2 * y + 1))) << x << "," << y;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) ASSERT_EQ((*l2)[size_t(y * 2 + x)], float(4 * x + 3 + 8 * (4 * y + 3))) << x << "," << y;
    auto l0 = gpu().readImage(*img, 0);
    ASSERT_TRUE(l0);
    EXPECT_EQ(*l0, base);
    gpu().destroy(*pipe);
    gpu().destroy(*img);
}

gpu::GraphicsPipelineDesc fullscreen(const std::string& fragmentBody, gpu::Format target) {
    gpu::GraphicsPipelineDesc d;
    d.vertex = {"fs", gpu::Stage::Vertex,
                "#version 450\nvoid main() {\n#ifdef VULKAN\n int id = gl_VertexIndex;\n#else\n int id = gl_VertexID;\n#endif\n"
                " vec2 p = vec2((id << 1) & 2, id & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n",
                {"<vs>"}};
    d.fragment = {"fs", gpu::Stage::Fragment, "#version 450\n" + fragmentBody, {"<fs>"}};
    d.colorFormats = {target};
    return d;
}

bool anyContains(const std::vector<std::string>& messages, const std::string& what) {
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(what) != std::string::npos; });
}

// Synchronisation validation is on in every test (vk_device.cpp): leaving out
// the barrier() between a compute store and a pass that samples the image, or
// between that sampling and a store that overwrites it, is reported; with the
// barrier() the same frames report nothing. The Debian 12 layer (1.3.239) does
// not track the attachments of dynamic rendering, so a missing barrier after a
// colour attachment write goes unreported there: that case checks only that
// the barrier() gives no false report.
TEST_P(Backend, MissingBarrierIsReportedBySynchronisationValidation) {
    if (api() == gpu::Api::OpenGL) GTEST_SKIP() << "GL's debug output has no synchronisation validation";
    if (!validationOn()) GTEST_SKIP() << "CAVITY_TEST_VALIDATION=0";
    auto a = gpu().createImage({8, 8, gpu::Format::R32F, 1, "written"});
    auto b = gpu().createImage({8, 8, gpu::Format::R32F, 1, "read back"});
    ASSERT_TRUE(a && b);
    auto store = gpu().createComputePipeline(levelMarker());
    auto render = gpu().createGraphicsPipeline(
        fullscreen("layout(location = 0) out vec4 o; void main() { o = vec4(3.0); }\n", gpu::Format::R32F));
    gpu::ComputePipelineDesc copy;
    copy.shader = compute(
        "layout(binding = 0) uniform sampler2D src;\n"
        "layout(binding = 1, r32f) uniform writeonly image2D dst;\n"
        "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
        "  imageStore(dst, p, texelFetch(src, p, 0)); }\n");
    copy.layout = {{0, gpu::BindingKind::SampledImage, {}}, {1, gpu::BindingKind::StorageImage, gpu::Format::R32F}};
    auto read = gpu().createComputePipeline(copy);
    ASSERT_TRUE(store && render && read);
    const gpu::Bind toA{0, *a, {}, {}};
    const gpu::Bind aToB[2] = {{0, *a, {}, {}}, {1, *b, {}, {}}};
    gpu::RenderTargets targets;
    targets.colors = {*a};
    const auto storeA = [&] { gpu().dispatch(*store, std::span(&toA, 1), 1, 1); };
    const auto renderA = [&] { gpu().draw(*render, {}, targets, 3); };
    const auto sampleA = [&] { gpu().dispatch(*read, aToB, 1, 1); };
    struct Case {
        const char* name;
        std::function<void()> first, second;
        const char* hazard;   // reported without the barrier(); null: not tracked
    };
    const Case cases[] = {
        {"compute store, then sampled", storeA, sampleA, "SYNC-HAZARD-READ-AFTER-WRITE"},
        {"sampled, then compute store", sampleA, storeA, "SYNC-HAZARD-WRITE-AFTER-READ"},
        {"colour attachment write, then sampled", renderA, sampleA, nullptr},
    };
    for (const Case& c : cases) {
        for (const bool withBarrier : {true, false}) {
            if (!withBarrier && !c.hazard) continue;
            const std::string what = std::string(c.name) + (withBarrier ? ", barrier()" : ", no barrier()");
            gpu().beginFrame();
            c.first();
            if (withBarrier) gpu().barrier();
            c.second();
            ASSERT_TRUE(gpu().endFrame().ok()) << what;
            const auto messages = gpu().takeDebugMessages();
            std::string all;
            for (const auto& m : messages) all += "\n  " + m;
            if (withBarrier) EXPECT_TRUE(messages.empty()) << what << all;
            else EXPECT_TRUE(anyContains(messages, c.hazard)) << what << all;
        }
    }
    gpu().destroy(*store);
    gpu().destroy(*render);
    gpu().destroy(*read);
    gpu().destroy(*a);
    gpu().destroy(*b);
}

// barrier() is recorded as late as the next command (vk_barriers.h, GL's
// owedBarrier), narrowed to it; it must still reach every command up to the
// next barrier(), and a write two barriers back through a barrier() between
// passes of another stage. Wrong values or a synchronisation-validation
// message fail the test.
TEST_P(Backend, BarrierReachesEveryPassUntilTheNextOne) {
    auto store = gpu().createComputePipeline(levelMarker());
    gpu::ComputePipelineDesc copy;
    copy.shader = compute(
        "layout(binding = 0) uniform sampler2D src;\n"
        "layout(binding = 1, r32f) uniform writeonly image2D dst;\n"
        "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
        "  imageStore(dst, p, texelFetch(src, p, 0)); }\n");
    copy.layout = {{0, gpu::BindingKind::SampledImage, {}}, {1, gpu::BindingKind::StorageImage, gpu::Format::R32F}};
    auto sampleInCompute = gpu().createComputePipeline(copy);
    auto renderDesc = fullscreen(
        "layout(binding = 0) uniform sampler2D src; layout(location = 0) out vec4 o;\n"
        "void main() { o = texelFetch(src, ivec2(gl_FragCoord.xy), 0); }\n",
        gpu::Format::R32F);
    renderDesc.layout = {{0, gpu::BindingKind::SampledImage, {}}};
    auto sampleInFragment = gpu().createGraphicsPipeline(renderDesc);
    ASSERT_TRUE(store && sampleInCompute && sampleInFragment);
    std::vector<gpu::Image> images;
    for (const char* name : {"a", "b", "c", "d"}) {
        auto img = gpu().createImage({8, 8, gpu::Format::R32F, 1, name});
        ASSERT_TRUE(img);
        images.push_back(*img);
    }
    const gpu::Image a = images[0], b = images[1], c = images[2], d = images[3];
    const auto storeTo = [&](gpu::Image img) {
        const gpu::Bind bind{0, img, {}, {}};
        gpu().dispatch(*store, std::span(&bind, 1), 1, 1);
    };
    const auto copyInCompute = [&](gpu::Image from, gpu::Image to) {
        const gpu::Bind binds[2] = {{0, from, {}, {}}, {1, to, {}, {}}};
        gpu().dispatch(*sampleInCompute, binds, 1, 1);
    };
    const auto copyInFragment = [&](gpu::Image from, gpu::Image to) {
        const gpu::Bind bind{0, from, {}, {}};
        gpu::RenderTargets t;
        t.colors = {to};
        gpu().draw(*sampleInFragment, std::span(&bind, 1), t, 3);
    };
    const auto expectAll = [&](gpu::Image img, float value, const char* what) {
        auto px = gpu().readImage(img);
        ASSERT_TRUE(px) << px.error().message;
        for (float v : *px) ASSERT_EQ(v, value) << what;
    };

    // One barrier(), then a compute and a fragment pass that both read what came before it.
    gpu().beginFrame();
    storeTo(a);
    gpu().barrier();
    copyInCompute(a, b);
    copyInFragment(a, c);
    ASSERT_TRUE(gpu().endFrame().ok());
    expectAll(b, 12.5f, "compute pass after the barrier");
    expectAll(c, 12.5f, "fragment pass after the same barrier");

    // A fragment pass two barriers after the store it reads, a compute pass between.
    gpu().beginFrame();
    storeTo(d);
    gpu().barrier();
    copyInCompute(a, b);
    gpu().barrier();
    copyInFragment(d, c);
    ASSERT_TRUE(gpu().endFrame().ok());
    expectAll(c, 12.5f, "fragment pass two barriers after the store");
    for (auto img : images) gpu().destroy(img);
    gpu().destroy(*store);
    gpu().destroy(*sampleInCompute);
    gpu().destroy(*sampleInFragment);
}

TEST_P(Backend, ImageUsageLimitsWhatAnImageIsFor) {
    auto sampledOnly = gpu().createImage({8, 8, gpu::Format::R32F, 1, "sampled", gpu::ImageSampled | gpu::ImageTransfer});
    auto storageOnly = gpu().createImage({8, 8, gpu::Format::R32F, 1, "stored", gpu::ImageStorage});
    auto pipe = gpu().createComputePipeline(levelMarker());
    ASSERT_TRUE(sampledOnly && storageOnly && pipe);
    ASSERT_TRUE(gpu().uploadImage(*sampledOnly, 0, std::vector<float>(64, 1.0f)).ok());
    EXPECT_TRUE(gpu().readImage(*sampledOnly));

    gpu::Bind bind{0, *storageOnly, {}, {}};
    gpu().beginFrame();
    gpu().dispatch(*pipe, std::span(&bind, 1), 1, 1);
    EXPECT_TRUE(gpu().endFrame().ok());
    auto back = gpu().readImage(*storageOnly);
    ASSERT_FALSE(back);
    EXPECT_NE(back.error().message.find("'stored' was created without ImageTransfer"), std::string::npos)
        << back.error().message;

    bind.image = *sampledOnly;
    gpu().beginFrame();
    gpu().dispatch(*pipe, std::span(&bind, 1), 1, 1);
    const Status s = gpu().endFrame();
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("'sampled' was created without ImageStorage"), std::string::npos)
        << s.error().message;
    gpu().destroy(*pipe);
    gpu().destroy(*sampledOnly);
    gpu().destroy(*storageOnly);
}

TEST_P(Backend, TimestampScopesComeBackInOrderWithPositiveTimes) {
    auto out = gpu().createImage({256, 256, gpu::Format::R32F, 1, "spin"});
    ASSERT_TRUE(out);
    gpu::ComputePipelineDesc d;
    d.shader = compute(
        "layout(binding = 0, r32f) uniform writeonly image2D o;\n"
        "void main() { float s = 0; for (int i = 0; i < 64; ++i) s += sin(float(i) * gl_GlobalInvocationID.x);\n"
        "  imageStore(o, ivec2(gl_GlobalInvocationID.xy), vec4(s)); }\n");
    d.layout = {{0, gpu::BindingKind::StorageImage, gpu::Format::R32F}};
    auto pipe = gpu().createComputePipeline(d);
    ASSERT_TRUE(pipe) << pipe.error().message;
    gpu::Bind b{0, *out, {}, {}};
    gpu().beginFrame();
    gpu().beginScope("outer");
    gpu().beginScope("first");
    gpu().dispatch(*pipe, std::span(&b, 1), 32, 32);
    gpu().endScope();
    gpu().barrier();
    gpu().beginScope("second");
    gpu().dispatch(*pipe, std::span(&b, 1), 32, 32);
    gpu().endScope();
    gpu().endScope();
    ASSERT_TRUE(gpu().endFrame().ok());
    const auto t = gpu().scopeTimes();
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].name, "outer");
    EXPECT_EQ(t[1].name, "first");
    EXPECT_EQ(t[2].name, "second");
    for (const auto& s : t) EXPECT_GE(s.gpuMs, 0.0) << s.name;
    EXPECT_GE(t[0].gpuMs, t[1].gpuMs);
    gpu().destroy(*pipe);
    gpu().destroy(*out);
}

TEST_P(Backend, CompileErrorNamesFileAndLine) {
    gpu::ComputePipelineDesc d;
    d.shader = {"broken", gpu::Stage::Compute,
                "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n#line 1 1\nvoid main() {\n"
                "  float x = undeclared_thing;\n}\n",
                {"<preamble>", "kernels/broken.glsl"}};
    auto pipe = gpu().createComputePipeline(d);
    ASSERT_FALSE(pipe);
    EXPECT_NE(pipe.error().message.find("kernels/broken.glsl:2"), std::string::npos) << pipe.error().message;
    gpu().takeDebugMessages();   // a failed compile may legitimately log
}

// What the driver says it compiled (VK_KHR_pipeline_executable_properties):
// where it reports statistics, each is named, and a kernel that keeps 32
// fetched vec4s alive at once takes more registers than one that keeps one.
// Where it reports none, the reason says why (the API or the missing
// extension): the CPU renderers CI runs report none.
TEST_P(Backend, PipelineStatisticsSayWhatTheDriverCompiled) {
    const std::string head =
        "layout(binding = 0, r32f) uniform writeonly image2D o;\n"
        "layout(std430, binding = 1) readonly buffer In { vec4 v[]; };\n";
    const std::string light = head + "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                                     "  imageStore(o, p, vec4(v[p.x].x)); }\n";
    const std::string heavy = head + "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                                     "  vec4 a[32]; for (int i = 0; i < 32; ++i) a[i] = v[p.x * 32 + i];\n"
                                     "  vec4 s = vec4(0); for (int i = 0; i < 32; ++i) s += a[i] * a[31 - i] * a[(i * 7) & 31];\n"
                                     "  imageStore(o, p, s); }\n";
    std::vector<gpu::PipelineInfo> infos;
    for (const auto& body : {light, heavy}) {
        gpu::ComputePipelineDesc d;
        d.shader = compute(body);
        d.layout = {{0, gpu::BindingKind::StorageImage, gpu::Format::R32F}, {1, gpu::BindingKind::StorageBuffer, {}}};
        auto pipe = gpu().createComputePipeline(d);
        ASSERT_TRUE(pipe) << pipe.error().message;
        infos.push_back(gpu().pipelineInfo(*pipe));
        gpu().destroy(*pipe);
    }
    for (const auto& info : infos) {
        EXPECT_EQ(info.stats.empty(), !info.statsReason.empty()) << info.statsReason;
        for (const auto& st : info.stats) {
            EXPECT_FALSE(st.executable.empty());
            EXPECT_FALSE(st.name.empty());
            std::printf("[ stats    ] %s %s: %s / %s = %g\n", apiName(api()), &info == &infos[0] ? "light" : "heavy",
                        st.executable.c_str(), st.name.c_str(), st.value);
        }
    }
    if (infos[0].stats.empty()) {
        const std::string expected = api() == gpu::Api::OpenGL ? "OpenGL" : "VK_KHR_pipeline_executable_properties";
        EXPECT_NE(infos[0].statsReason.find(expected), std::string::npos) << infos[0].statsReason;
        return;
    }
    if (gpu::registerCount(infos[0].stats) >= 0) {
        EXPECT_GT(gpu::registerCount(infos[1].stats), gpu::registerCount(infos[0].stats));
    }
}

// The register count under the names drivers give it: the most over the
// pipeline's stages; AMD's scalar registers are not a thread's.
TEST(PipelineStatistics, RegisterCountReadsTheDriversNames) {
    gpu::PipelineInfo info;
    EXPECT_EQ(gpu::registerCount(info.stats), -1);
    info.stats = {{"Vertex Shader", "Register Count", 12}, {"Fragment Shader", "Register Count", 40},
                  {"Fragment Shader", "Binary Size", 4096}};
    EXPECT_EQ(gpu::registerCount(info.stats), 40);
    info.stats = {{"Compute Shader", "SGPRs", 96}, {"Compute Shader", "VGPRs", 24}};
    EXPECT_EQ(gpu::registerCount(info.stats), 24);
    info.stats = {{"Compute Shader", "Instruction Count", 300}};
    EXPECT_EQ(gpu::registerCount(info.stats), -1);
}

CAVITY_ALL_BACKENDS(Backend);

}  // namespace
}  // namespace cavity::test
