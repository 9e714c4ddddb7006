// The imported G-buffer (--gbuffer import, harness/images/gbuffer_import.h).
//
//  * Round trip, both APIs: the corner G-buffer the harness renders, written
//    to one EXR (P.*, N.*, albedo.*, float) and imported, must come back bit
//    for bit (normals within 1e-3 of unit length are not renormalised, so
//    the half-float normals return unchanged), and every screen-space AO
//    pipeline (full and half resolution) run on it must give bit-identical
//    AO, blurred AO and composite: tolerance 0. A control with the rows
//    flipped must fail that comparison.
//  * Depth only (Z, N.*, albedo.*): x and y are rebuilt through the pixel
//    centre; they must match the rendered position within 2e-6 of the
//    linear depth (float rounding of the two constructions, a few ulps;
//    measured 2.4e-7 on llvmpipe and lavapipe), z and w exactly, background
//    exactly; the AO on it within 2e-3 (a moved position may move one
//    sample to another pixel on some driver; measured 4.8e-7).
//  * Bad input through the cavity binary: exit 2, one line naming the flag or
//    file and the value, nothing written into --out.
#include "run_binary.h"
#include "core/camera.h"
#include "images/gbuffer_import.h"
#include "gpu_fixture.h"
#include "images/image_io.h"
#include "pipeline/pipeline.h"
#include "plan/sweep.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

namespace fs = std::filesystem;

namespace cavity::test {
namespace {

constexpr int kW = 160, kH = 90;

using Channels = std::vector<std::pair<std::string, std::vector<float>>>;

// One EXR with the named planes (each width x height floats, rows top down).
void writeExr(const fs::path& path, int w, int h, const Channels& channels, const char* compression = "zip") {
    OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (const auto& c : channels) spec.channelnames.push_back(c.first);
    spec.attribute("compression", compression);
    std::vector<float> px(size_t(w) * h * channels.size());
    for (size_t c = 0; c < channels.size(); ++c)
        for (size_t i = 0; i < size_t(w) * h; ++i) px[i * channels.size() + c] = channels[c].second[i];
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
}

std::vector<float> plane(const HostImage& img, int c, bool flipRows = false) {
    std::vector<float> v(size_t(img.width) * img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            v[size_t(y) * img.width + x] = img.at(x, flipRows ? img.height - 1 - y : y, c);
    return v;
}

fs::path tempDir(const std::string& what) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "-" + info->name() + "-" + what;
    for (char& ch : name)
        if (ch == '/') ch = '_';
    const fs::path d = fs::temp_directory_path() / ("cavity-import-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

RunConfig cornerConfig(gpu::Api api, const std::string& kernel = "alchemy", bool half = false) {
    RunConfig c;
    c.api = api;
    c.width = kW;
    c.height = kH;
    c.kernel = kernel;
    c.half = half;
    EXPECT_TRUE(setParam(c, "scene", "corner").ok());
    return c;
}

using Images = std::map<std::string, HostImage>;

// Runs one frame of a configuration and reads the named images back.
Images render(gpu::Backend& gpu, const RunConfig& c, const std::vector<std::string>& names) {
    Images out;
    auto chain = PassChain::create(gpu, c);
    EXPECT_TRUE(chain) << chain.error().message;
    if (!chain) return out;
    gpu.beginFrame();
    (*chain)->record();
    const auto st = gpu.endFrame();
    EXPECT_TRUE(st.ok()) << st.error().message;
    for (const auto& n : names) {
        auto img = (*chain)->read(n);
        EXPECT_TRUE(img) << n << ": " << img.error().message;
        if (img) out[n] = std::move(*img);
    }
    return out;
}

RunConfig importedConfig(RunConfig c, const fs::path& file) {
    c.gbufferFile = file.string();
    auto g = importGBuffer(c.gbufferFile, c.width, c.height);
    EXPECT_TRUE(g) << g.error().message;
    if (g) c.gbufferImages = std::make_shared<const GBufferImages>(std::move(*g));
    return c;
}

Channels fullCapture(const Images& gb, bool flipRows = false) {
    return {{"P.X", plane(gb.at("position"), 0, flipRows)}, {"P.Y", plane(gb.at("position"), 1, flipRows)},
            {"P.Z", plane(gb.at("position"), 2, flipRows)}, {"N.X", plane(gb.at("normal"), 0, flipRows)},
            {"N.Y", plane(gb.at("normal"), 1, flipRows)},   {"N.Z", plane(gb.at("normal"), 2, flipRows)},
            {"albedo.R", plane(gb.at("albedo"), 0, flipRows)}, {"albedo.G", plane(gb.at("albedo"), 1, flipRows)},
            {"albedo.B", plane(gb.at("albedo"), 2, flipRows)}};
}

class ImportRoundTrip : public GpuTest {};

TEST_P(ImportRoundTrip, EveryScreenSpacePipelineMatchesTheGeneratedGBuffer) {
    const fs::path dir = tempDir("rt");
    const std::vector<std::string> gbufferNames{"position", "normal", "albedo"};
    const Images gb = render(gpu(), cornerConfig(api()), gbufferNames);
    ASSERT_EQ(gb.size(), 3u);
    const fs::path file = dir / "corner_capture.exr";
    writeExr(file, kW, kH, fullCapture(gb));

    // The imported images themselves: bit for bit.
    auto g = importGBuffer(file.string(), kW, kH);
    ASSERT_TRUE(g) << g.error().message;
    EXPECT_EQ(g->position.pixels, gb.at("position").pixels);
    EXPECT_EQ(g->normal.pixels, gb.at("normal").pixels);
    EXPECT_EQ(g->albedo.pixels, gb.at("albedo").pixels);

    // Every AO pipeline that reads only the G-buffer, on the upload.
    int pipelines = 0;
    for (const auto& kernel : aoKernels()) {
        bool scene = false;
        for (const auto& p : kernels::find(kernel)->params) scene |= p.name() == "scene";
        if (scene) continue;
        for (bool half : {false, true}) {
            if (half && !supportsHalf(kernel)) continue;
            ++pipelines;
            const RunConfig generated = cornerConfig(api(), kernel, half);
            const RunConfig imported = importedConfig(generated, file);
            ASSERT_TRUE(validate(imported).ok()) << validate(imported).error().message;
            std::vector<std::string> names{"ao", "ao_blur", "color"};
            for (const auto& n : gbufferNames) names.push_back(n);
            names.push_back("linear_depth");   // made from the imported position's w
            const Images a = render(gpu(), generated, names), b = render(gpu(), imported, names);
            for (const auto& n : names) {
                ASSERT_TRUE(a.count(n) && b.count(n)) << kernel << " " << n;
                const Diff d = diff(a.at(n), b.at(n));
                EXPECT_EQ(d.maxAbs, 0.0) << kernel << (half ? " half " : " full ") << n << ": worst at (" << d.worstX
                                         << ", " << d.worstY << ")";
                if (n == "ao")
                    std::printf("%s %s %s: imported vs generated AO max |d| %g, mean %g\n", gpu::apiName(api()),
                                kernel.c_str(), half ? "half" : "full", d.maxAbs, d.meanAbs);
            }
        }
    }
    EXPECT_GE(pipelines, 3);

    // Control: the same capture upside down (a wrong row convention) must
    // not pass the comparison above.
    const fs::path flipped = dir / "flipped.exr";
    writeExr(flipped, kW, kH, fullCapture(gb, true));
    const RunConfig generated = cornerConfig(api());
    const Images a = render(gpu(), generated, {"ao"}), b = render(gpu(), importedConfig(generated, flipped), {"ao"});
    ASSERT_TRUE(a.count("ao") && b.count("ao"));
    EXPECT_GT(diff(a.at("ao"), b.at("ao")).maxAbs, 0.1);
    fs::remove_all(dir);
}

TEST_P(ImportRoundTrip, DepthOnlyCaptureRebuildsThePosition) {
    const fs::path dir = tempDir("z");
    const RunConfig generated = cornerConfig(api());
    const Images gb = render(gpu(), generated, {"position", "normal", "albedo", "ao"});
    ASSERT_EQ(gb.size(), 4u);
    const HostImage& pos = gb.at("position");
    Channels ch = fullCapture(gb);
    ch.erase(ch.begin(), ch.begin() + 3);   // no P.*
    ch.push_back({"Z", plane(pos, 3)});
    const fs::path file = dir / "depth_only.exr";
    writeExr(file, kW, kH, ch);

    auto g = importGBuffer(file.string(), kW, kH);
    ASSERT_TRUE(g) << g.error().message;
    const HostImage& rebuilt = g->position;
    double worstRel = 0;
    long long surface = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float depth = pos.at(x, y, 3);
            if (depth <= 0) {
                for (int k = 0; k < 4; ++k) ASSERT_EQ(rebuilt.at(x, y, k), 0.0f) << x << "," << y;
                continue;
            }
            ++surface;
            EXPECT_EQ(rebuilt.at(x, y, 2), pos.at(x, y, 2)) << x << "," << y;
            EXPECT_EQ(rebuilt.at(x, y, 3), depth) << x << "," << y;
            for (int k = 0; k < 2; ++k) {
                const double rel = std::fabs(double(rebuilt.at(x, y, k)) - pos.at(x, y, k)) / depth;
                worstRel = std::max(worstRel, rel);
                EXPECT_LE(rel, 2e-6) << "pixel " << x << "," << y << " axis " << k;
            }
        }
    EXPECT_GT(surface, kW * kH / 2);
    EXPECT_EQ(g->normal.pixels, gb.at("normal").pixels);

    // The AO on the rebuilt positions: not bit-identical (positions moved by
    // a few ulps), but within 2e-3 everywhere.
    const Images b = render(gpu(), importedConfig(generated, file), {"ao"});
    ASSERT_TRUE(b.count("ao"));
    const Diff d = diff(gb.at("ao"), b.at("ao"));
    std::printf("%s depth-only: position max |d|/depth %.3g; AO max |d| %.3g, mean %.3g\n", gpu::apiName(api()),
                worstRel, d.maxAbs, d.meanAbs);
    EXPECT_LE(d.maxAbs, 2e-3);
    fs::remove_all(dir);
}

CAVITY_ALL_BACKENDS(ImportRoundTrip);

// --- through the cavity binary ----------------------------------------------

using ::cavity::test::Outcome;

Outcome cavity(const std::string& args) {
    return ::cavity::test::runBinary(CAVITY_EXE, args);
}

// A plane facing the camera at depth 2 (P.* or Z), 32x18.
constexpr int kSw = 32, kSh = 18;
Channels planeCapture(bool depthOnly) {
    const size_t n = size_t(kSw) * kSh;
    Channels c;
    if (depthOnly) {
        c.push_back({"Z", std::vector<float>(n, 2.0f)});
    } else {
        const auto frame = frameUniforms(kSw, kSh, kSw, kSh);
        std::vector<float> px(n), py(n), pz(n, -2.0f);
        for (int y = 0; y < kSh; ++y)
            for (int x = 0; x < kSw; ++x) {
                px[size_t(y) * kSw + x] = ((x + 0.5f) / kSw * 2 - 1) * frame.camera[0] * 2.0f;
                py[size_t(y) * kSw + x] = -((y + 0.5f) / kSh * 2 - 1) * frame.camera[1] * 2.0f;
            }
        c.push_back({"P.X", px});
        c.push_back({"P.Y", py});
        c.push_back({"P.Z", pz});
    }
    c.push_back({"N.X", std::vector<float>(n, 0.0f)});
    c.push_back({"N.Y", std::vector<float>(n, 0.0f)});
    c.push_back({"N.Z", std::vector<float>(n, 1.0f)});
    return c;
}

class ImportCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = tempDir("files");
        out = dir / "out";
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir, out;
};

struct BadCase {
    std::string what;
    std::string args;
    std::string message;   // the one line expected on stderr
};

TEST_F(ImportCli, BadInputExitsTwoWithOneLineAndWritesNothing) {
    const std::string good = (dir / "plane.exr").string();
    writeExr(good, kSw, kSh, planeCapture(false));

    Channels noNy = planeCapture(false);
    noNy.erase(noNy.begin() + 4);   // N.Y
    const std::string missing = (dir / "no_ny.exr").string();
    writeExr(missing, kSw, kSh, noNy);

    Channels nan = planeCapture(false);
    nan[4].second[size_t(2) * kSw + 3] = std::numeric_limits<float>::quiet_NaN();   // N.Y at (3, 2)
    const std::string nanFile = (dir / "nan_ny.exr").string();
    writeExr(nanFile, kSw, kSh, nan);

    Channels inf = planeCapture(true);
    inf[0].second[5] = std::numeric_limits<float>::infinity();   // Z at (5, 0)
    const std::string infFile = (dir / "inf_z.exr").string();
    writeExr(infFile, kSw, kSh, inf);

    Channels zeroN = planeCapture(false);
    zeroN[5].second[7] = 0.0f;   // N.Z at (7, 0): normal (0, 0, 0)
    const std::string zeroFile = (dir / "zero_n.exr").string();
    writeExr(zeroFile, kSw, kSh, zeroN);

    const std::string png = (dir / "capture.png").string();
    ASSERT_TRUE(writeImage(png, HostImage(kSw, kSh, 4, 0.5f)).ok());

    // The plane, uncompressed (a chunk a row), with both windows' last row
    // moved to 16383 and the offset table grown to match: a header of 16384
    // rows over a file that holds 18 (it once allocated them all, then failed).
    const std::string cut = (dir / "cut.exr").string();
    {
        writeExr(cut, kSw, kSh, planeCapture(false), "none");
        std::ifstream in(cut, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        for (const std::string window : {"dataWindow", "displayWindow"}) {
            const std::string tag = window + std::string("\0box2i\0", 7);
            const size_t at = bytes.find(tag);
            ASSERT_NE(at, std::string::npos) << window;
            const int32_t last = 16383;   // yMax: after the size (4) and xMin, yMin, xMax
            std::memcpy(&bytes[at + tag.size() + 4 + 12], &last, 4);
        }
        // The table starts where its first offset, less the table, points.
        size_t table = 0;
        for (size_t p = 0; p + 8 <= bytes.size() && !table; ++p) {
            uint64_t v;
            std::memcpy(&v, &bytes[p], 8);
            if (v == p + 8 * kSh) table = p;
        }
        ASSERT_NE(table, 0u);
        const uint64_t grown = 8 * (16384 - kSh);
        for (int row = 0; row < kSh; ++row) {
            uint64_t v;
            std::memcpy(&v, &bytes[table + 8 * row], 8);
            v += grown;
            std::memcpy(&bytes[table + 8 * row], &v, 8);
        }
        bytes.insert(table + 8 * kSh, std::string(grown, '\0'));
        std::ofstream(cut, std::ios::binary | std::ios::trunc) << bytes;
    }

    const std::string absent = (dir / "absent.exr").string();
    const std::string head = "cavity run: --gbuffer-file ";
    std::vector<BadCase> cases = {
        {"missing file", "--gbuffer import --gbuffer-file " + absent, head + absent + ": no such file"},
        {"missing channel", "--gbuffer import --gbuffer-file " + missing,
         head + missing + ": no channel N.Y: need N.X, N.Y, N.Z (the file has: "},
        {"wrong size", "--gbuffer import --gbuffer-file " + good + " --res 64x36",
         head + good + ": wrong size 32x18: must be the run's --res 64x36"},
        {"NaN in N.Y", "--gbuffer import --gbuffer-file " + nanFile,
         head + nanFile + ": channel N.Y is nan at pixel (3, 2): must be finite"},
        {"inf in Z", "--gbuffer import --gbuffer-file " + infFile,
         head + infFile + ": channel Z is inf at pixel (5, 0): must be finite"},
        {"zero normal", "--gbuffer import --gbuffer-file " + zeroFile,
         head + zeroFile + ": channels N.X, N.Y, N.Z are (0, 0, 0) at pixel (7, 0), a surface pixel"},
        {"header past the file", "--gbuffer import --gbuffer-file " + cut,
         head + cut + ": cut short: its header says 32x16384, which needs at least 262144 bytes, and the file has "},
        {"not an EXR", "--gbuffer import --gbuffer-file " + png,
         head + png + ": is a png file: must be a multi-channel OpenEXR file"},
        {"file without import", "--gbuffer-file " + good, head + good + ": only used with --gbuffer import"},
        {"file with sdf", "--gbuffer sdf --gbuffer-file " + good, head + good + ": only used with --gbuffer import"},
        {"import without file", "--gbuffer import", "cavity run: --gbuffer import: needs --gbuffer-file FILE"},
        {"unknown source", "--gbuffer capture", "cavity run: --gbuffer capture: must be sdf, raster or import"},
        {"scene with import", "--gbuffer import --scene corner --gbuffer-file " + good,
         "cavity run: --scene corner: not used with --gbuffer import"},
    };
    // A kernel that evaluates the analytic scene, found by its declaration,
    // not its name.
    std::string sceneKernel;
    for (const auto& k : kernels::all())
        if (k.role == cavity::kernels::Role::Ao && kernels::evaluatesScene(k) && sceneKernel.empty()) sceneKernel = k.name;
    ASSERT_FALSE(sceneKernel.empty()) << "the SDF AO kernels declare a scene parameter";
    cases.push_back({"scene kernel", "--gbuffer import --gbuffer-file " + good + " --kernel " + sceneKernel,
                     "cavity run: --kernel " + sceneKernel + ": pass ao (" + sceneKernel +
                         ") evaluates the analytic scene, so it cannot run on an imported G-buffer"});

    for (const auto& c : cases) {
        const Outcome o = cavity("run " + c.args + " --backend vk --frames 1 --warmup 0 --out " + out.string());
        EXPECT_EQ(o.code, 2) << c.what << "\n" << o.output;
        EXPECT_EQ(o.output.rfind(c.message, 0), 0u) << c.what << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << c.what << "\n" << o.output;
        EXPECT_FALSE(fs::exists(out)) << c.what;
    }
}

TEST_F(ImportCli, RunOnACaptureWritesImagesAndResults) {
    const fs::path file = dir / "my capture.exr";   // a space: the id replaces it
    writeExr(file, kSw, kSh, planeCapture(true));
    const Outcome o = cavity("run --backend all --gbuffer import --gbuffer-file '" + file.string() +
                             "' --samples 8 --blur 2 --frames 2 --warmup 0 --out " + out.string());
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(out / "results.json");
    ASSERT_TRUE(f) << o.output;
    const auto doc = nlohmann::json::parse(f);
    ASSERT_EQ(doc["runs"].size(), 2u);
    for (const auto& r : doc["runs"]) {
        const std::string api = r["backend"];
        EXPECT_EQ(r["id"], "my_capture+import/alchemy/n8/b2/full/32x18/" + api + "/compute");
        EXPECT_EQ(r["config"]["scene"], "my_capture");
        EXPECT_EQ(r["config"]["gbuffer"]["source"], "import");
        EXPECT_EQ(r["config"]["gbuffer"]["file"], file.string());
        EXPECT_EQ(r["config"]["width"], kSw);
        for (const auto& p : r["passes"]) EXPECT_NE(p["name"], "gbuffer") << "an upload is not a timed pass";
        EXPECT_EQ(r["passes"][0]["name"], "ao");
        const fs::path id = out / r["id"].get<std::string>();
        for (const char* name : {"ao.exr", "ao.png", "ao_blur.png", "color.png", "normal.png"})
            EXPECT_TRUE(fs::exists(id / name)) << (id / name);
        // A plane facing the camera occludes nothing.
        auto ao = readImage((id / "ao.exr").string());
        ASSERT_TRUE(ao) << ao.error().message;
        for (float v : ao->pixels) ASSERT_NEAR(v, 1.0f, 1e-3);
    }
}

}  // namespace
}  // namespace cavity::test
