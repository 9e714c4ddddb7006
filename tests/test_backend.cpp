// Backend conformance: the contract of backends/backend.h, one body per API.
#include "gpu_fixture.h"
#include "kernel_runner.h"

#include <chrono>
#include <cstring>

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
    for (auto f : {gpu::Format::R8, gpu::Format::R16F, gpu::Format::R32F, gpu::Format::RG16F, gpu::Format::RGBA8,
                   gpu::Format::RGBA16F, gpu::Format::RGBA32F, gpu::Format::D32}) {
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

CAVITY_ALL_BACKENDS(Backend);

}  // namespace
}  // namespace cavity::test
