// Each pass's floor (harness/measure/roofline.h): the arithmetic against numbers
// worked by hand for the H200's table entry, where each figure comes from,
// the cases with no floor, every declaration's cost being complete, and
// docs/roofline.md's table being what the code computes.
#include "harness_names.h"
#include "core/config.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "measure/roofline.h"
#include "compiler/compiler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace cavity {

using namespace cavity::harness;
namespace {

gpu::DeviceInfo device(const std::string& name, int smCount = 0, bool software = false) {
    gpu::DeviceInfo d;
    d.api = "vk";
    d.deviceName = name;
    d.smCount = smCount;
    d.softwareRenderer = software;
    return d;
}

constexpr double kPixels1080p = 1920.0 * 1080.0;   // 2 073 600

TEST(Roofline, H200TableEntryGivesEveryFigureWithItsSource) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    ASSERT_TRUE(d.figures) << d.reason;
    EXPECT_EQ(d.reason, "");
    EXPECT_EQ(d.figures->smCount.value, 132);
    EXPECT_EQ(d.figures->textureUnitsPerSm.value, 4);
    EXPECT_EQ(d.figures->smClockMhz.value, 1980);
    EXPECT_EQ(d.figures->dramGBps.value, 4800);
    for (const Figure* f : {&d.figures->smCount, &d.figures->textureUnitsPerSm, &d.figures->smClockMhz, &d.figures->dramGBps})
        EXPECT_EQ(f->source, "table:NVIDIA H200");
    // 132 x 4 x 1.98 GHz.
    EXPECT_DOUBLE_EQ(d.figures->slotsPerSecond(), 1.04544e12);
}

// Alchemy, n = 16, at 1920x1080: 2 + 16 fetches; slots 4 (position) + 2
// (normal) + 16 x 4 (RGBA32F positions) = 70; DRAM 16 + 8 read + 2 written
// = 26 bytes. In ms, fetch: 1e3 x 2073600 x 70 / 1.04544e12 = 0.138843;
// DRAM: 1e3 x 2073600 x 26 / 4.8e12 = 0.011232.
TEST(Roofline, AlchemyN16At1080pOnTheH200) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    const PassFloorResult r = passFloor(d, "alchemy", {{"samples", 16}}, kPixels1080p);
    ASSERT_TRUE(r.floor) << r.reason;
    EXPECT_EQ(r.floor->cost.fetchesPerPixel, 18);
    EXPECT_EQ(r.floor->cost.fetchSlotsPerPixel, 70);
    EXPECT_EQ(r.floor->cost.bytesPerPixel, 282);
    EXPECT_EQ(r.floor->cost.dramBytesPerPixel, 26);
    EXPECT_NEAR(r.floor->fetchMs, 0.1388429752, 1e-9);
    EXPECT_NEAR(r.floor->dramMs, 0.011232, 1e-9);
    EXPECT_NEAR(r.floor->ms(), 0.1388429752, 1e-9);
    EXPECT_STREQ(r.floor->bound(), "fetch");
}

// The bilateral blur at r = 4: 81 taps of R16F + RGBA32F + RGBA16F, 7 slots
// each = 567; in ms, 1e3 x 2073600 x 567 / 1.04544e12 = 1.124628.
TEST(Roofline, BlurR4At1080pOnTheH200) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    const PassFloorResult r = passFloor(d, "blur_bilateral", {}, kPixels1080p);
    ASSERT_TRUE(r.floor) << r.reason;
    EXPECT_EQ(r.floor->cost.fetchSlotsPerPixel, 567);
    EXPECT_NEAR(r.floor->fetchMs, 1.1246280992, 1e-9);
}

// The ray-marched G-buffer fetches nothing: only its 32 bytes written, so
// DRAM-bound at, in ms, 1e3 x 2073600 x 32 / 4.8e12 = 0.013824.
TEST(Roofline, GBufferIsDramBound) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    const PassFloorResult r = passFloor(d, "gbuffer_sdf", {}, kPixels1080p);
    ASSERT_TRUE(r.floor) << r.reason;
    EXPECT_EQ(r.floor->fetchMs, 0);
    EXPECT_NEAR(r.floor->dramMs, 0.013824, 1e-9);
    EXPECT_STREQ(r.floor->bound(), "dram");
}

// The driver's SM count and NVML's clock win over the table, and GL's
// renderer string ("NVIDIA H200/PCIe/SSE2") finds the same entry.
TEST(Roofline, DriverAndNvmlFiguresWinOverTheTable) {
    gpu::DeviceInfo gl = device("NVIDIA H200/PCIe/SSE2", 66);
    gl.api = "gl";
    const DeviceFloor d = deviceFloor(gl, 1755.0);
    ASSERT_TRUE(d.figures) << d.reason;
    EXPECT_EQ(d.figures->name, "NVIDIA H200");
    EXPECT_EQ(d.figures->smCount.value, 66);
    EXPECT_EQ(d.figures->smCount.source, "driver");
    EXPECT_EQ(d.figures->smClockMhz.value, 1755);
    EXPECT_EQ(d.figures->smClockMhz.source, "nvml");
    EXPECT_EQ(d.figures->textureUnitsPerSm.source, "table:NVIDIA H200");
    const PassFloorResult r = passFloor(d, "alchemy", {}, kPixels1080p);
    ASSERT_TRUE(r.floor);
    EXPECT_NEAR(r.floor->fetchMs, 1e3 * kPixels1080p * 70 / (66 * 4 * 1755e6), 1e-12);
    EXPECT_EQ(describe(d), "NVIDIA H200: 66 SMs (driver) x 4 texture units/SM (table:NVIDIA H200) x 1755 MHz (nvml); "
                           "DRAM 4800 GB/s (table:NVIDIA H200); launch vk 3.65 us + 0.58 ns a workgroup, gl 6.05 us + "
                           "0.58 ns a workgroup");
}

// The launch term, worked by hand: each dispatch's fixed cost on the API
// and each workgroup's start, added to the memory floor; a pass that only
// launches is "launch" bound. Where the model has no term (a fragment
// pass, unknown dispatches, a device with no launch figures) it adds
// nothing and says why.
TEST(Roofline, LaunchTermCountsDispatchesAndWorkgroupsPerApi) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    const kernels::PassShape one{true, {16, 16}, 1, 120 * 68};
    const auto vk = passFloor(d, "composite", {}, kPixels1080p, one, gpu::Api::Vulkan);
    const auto gl = passFloor(d, "composite", {}, kPixels1080p, one, gpu::Api::OpenGL);
    ASSERT_TRUE(vk.floor && gl.floor);
    EXPECT_NEAR(vk.floor->launchMs, 1e-3 * 3.65 + 1e-6 * 8160 * 0.58, 1e-12);
    EXPECT_NEAR(gl.floor->launchMs - vk.floor->launchMs, 1e-3 * (6.05 - 3.65), 1e-12);
    EXPECT_NEAR(vk.floor->ms(), vk.floor->memoryMs() + vk.floor->launchMs, 1e-15);
    EXPECT_STREQ(vk.floor->bound(), "launch");   // the composite launches more than it fetches
    // Five dispatches (a per-level pyramid) pay the fixed part five times.
    const auto chain = passFloor(d, "composite", {}, kPixels1080p, kernels::PassShape{true, {16, 16}, 5, 8160});
    EXPECT_NEAR(chain.floor->launchMs - vk.floor->launchMs, 4e-3 * 3.65, 1e-12);
    const auto fragment = passFloor(d, "composite", {}, kPixels1080p, kernels::PassShape{false, {16, 16}});
    EXPECT_EQ(fragment.floor->launchMs, 0);
    EXPECT_NE(fragment.floor->launchReason.find("fragment"), std::string::npos);
    EXPECT_EQ(passFloor(d, "composite", {}, kPixels1080p).floor->launchReason, "no dispatch given");
    DeviceFloor unmeasured = d;
    unmeasured.figures->launchGl.reset();
    const auto none = passFloor(unmeasured, "composite", {}, kPixels1080p, one, gpu::Api::OpenGL);
    EXPECT_EQ(none.floor->launchMs, 0);
    EXPECT_EQ(none.floor->launchReason, "no launch figures measured for NVIDIA H200 on gl");
}

TEST(Roofline, SoftwareRendererHasNoFloor) {
    const DeviceFloor d = deviceFloor(device("llvmpipe (LLVM 15.0.6, 256 bits)", 0, true), std::nullopt);
    EXPECT_FALSE(d.figures);
    EXPECT_EQ(d.reason, "software renderer (llvmpipe (LLVM 15.0.6, 256 bits)): no GPU floor");
    const PassFloorResult r = passFloor(d, "alchemy", {}, kPixels1080p);
    EXPECT_FALSE(r.floor);
    EXPECT_EQ(r.reason, d.reason);
    EXPECT_EQ(describe(d), "no floor: " + d.reason);
}

TEST(Roofline, UnknownDeviceHasNoFloor) {
    // A name that merely starts like a table entry is not that entry.
    for (const std::string name : {"AMD Radeon RX 7900 XTX", "NVIDIA H200 NVL", "NVIDIA H20"}) {
        const DeviceFloor d = deviceFloor(device(name, 78), 2100.0);
        EXPECT_FALSE(d.figures) << name;
        EXPECT_EQ(d.reason, "device '" + name + "' is not in the floor table (harness/measure/roofline.cpp)");
        EXPECT_FALSE(passFloor(d, "alchemy", {}, kPixels1080p).floor);
    }
}

TEST(Roofline, NoCostDeclaredHasNoFloor) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    // The rasterised G-buffer is a graphics pass with no declaration.
    EXPECT_EQ(passFloor(d, "gbuffer_raster", {}, kPixels1080p).reason, "no cost declared");
    auto& registry = kernels::registryForTests();
    auto it = std::find_if(registry.begin(), registry.end(), [](const auto& k) { return k.name == "composite"; });
    ASSERT_NE(it, registry.end());
    const auto saved = it->cost;
    it->cost = nullptr;
    const PassFloorResult none = passFloor(d, "composite", {}, kPixels1080p);
    // A cost written before the floor existed: fetches and bytes only.
    it->cost = [](const kernels::ParamValues&, const kernels::PassShape&) { return kernels::Cost{3, 18}; };
    const PassFloorResult partial = passFloor(d, "composite", {}, kPixels1080p);
    it->cost = saved;
    EXPECT_FALSE(none.floor);
    EXPECT_EQ(none.reason, "no cost declared");
    EXPECT_FALSE(partial.floor);
    EXPECT_EQ(partial.reason, "cost declares no fetch slots or no DRAM bytes (kernels/kernel.h Cost)");
    EXPECT_TRUE(passFloor(d, "composite", {}, kPixels1080p).floor);
}

// Every declaration's cost fills the floor's fields: a kernel added with
// only fetches and bytes fails here, not silently in results.json.
TEST(Roofline, EveryDeclaredCostIsComplete) {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    for (const auto& k : kernels::all()) {
        ASSERT_TRUE(k.cost) << k.name << ": no cost declared";
        const PassFloorResult r = passFloor(d, k.name, {}, kPixels1080p);
        ASSERT_TRUE(r.floor) << k.name << ": " << r.reason;
        const kernels::Cost& c = r.floor->cost;
        EXPECT_EQ(c.fetchesPerPixel > 0, c.fetchSlotsPerPixel > 0) << k.name;
        // At least one slot per fetch, at most four (RGBA32F) or eight (trilinear).
        EXPECT_GE(c.fetchSlotsPerPixel, c.fetchesPerPixel) << k.name;
        EXPECT_LE(c.fetchSlotsPerPixel, 8 * c.fetchesPerPixel) << k.name;
        EXPECT_GT(c.bytesPerPixel, 0) << k.name;
    }
}

// --- tiled passes -----------------------------------------------------------

// Whether SPIR-V declares a variable in workgroup memory: an OpVariable
// (opcode 59: count and opcode, type, id, storage class) of storage class
// Workgroup (4).
bool declaresWorkgroupMemory(const std::vector<uint32_t>& spirv) {
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t count = spirv[i] >> 16, opcode = spirv[i] & 0xffff;
        if (count == 0) break;
        if (opcode == 59 && i + 3 < spirv.size() && spirv[i + 3] == 4) return true;
        i += count;
    }
    return false;
}

// A tiled pass's cost counts the tile's fetches exactly where its shader
// builds the tile: the C++ model (blurKeyFetches, upsampleCost) restates
// the shader's conditions (include/blur_separable.glsl, include/upsample.glsl),
// and this holds the two together. For each kernel, workgroup shape
// (CAVITY_WORKGROUP: declared, square, too large for the blur's tile, odd
// for the upsample's) and blur radius, the compute shader is compiled and
// its SPIR-V read for workgroup memory; the cost in that shape must count
// fewer fetches than the fragment stage's (every tap) exactly when it does.
TEST(Roofline, TiledCostWhereTheShaderTiles) {
    struct Env {
        ~Env() { unsetenv("CAVITY_WORKGROUP"); }
    } restore;
    int tiled = 0, untiled = 0;
    for (const std::string name : {"blur_separable_x", "blur_separable_y", "blur_separable_ssdo_x",
                                   "blur_separable_ssdo_y", "upsample_bilateral", "upsample_composite"}) {
        const kernels::KernelDecl* k = kernels::find(name);
        ASSERT_TRUE(k) << name;
        // An odd side stops the upsample's tile; a blur's tile one pixel
        // across its axis would load its 2r + 1 taps a pixel (no saving to
        // see), so the blurs take even shapes.
        const bool upsample = name.starts_with("upsample");
        for (const char* shape : {"", "8x8", "32x32", upsample ? "1x32" : "64x4", upsample ? "32x1" : "4x64"})
            for (const double radius : {1.0, 4.0, 32.0}) {
                setenv("CAVITY_WORKGROUP", shape, 1);   // empty: the kernel's own
                const auto wg = kernels::workgroupSize(*k);
                ASSERT_TRUE(wg) << wg.error().message;
                const kernels::ParamValues v = kernels::withDefaults(*k, {{"blur", radius}});
                auto src = kernels::assemble(*k, gpu::Stage::Compute, {}, &v);
                ASSERT_TRUE(src) << name << ": " << src.error().message;
                const auto spirv = kernels::compileToSpirv(*src, gpu::Api::Vulkan);
                ASSERT_TRUE(spirv) << name << ": " << spirv.error().message;
                const bool shaderTiles = declaresWorkgroupMemory(*spirv);
                const kernels::Cost compute = k->cost(v, {true, *wg}), fragment = k->cost(v, {false, *wg});
                EXPECT_EQ(compute.fetchesPerPixel < fragment.fetchesPerPixel, shaderTiles)
                    << name << " in " << wg->x << "x" << wg->y << ", r = " << radius << ": the cost counts "
                    << compute.fetchesPerPixel << " fetches a pixel, the fragment stage's " << fragment.fetchesPerPixel;
                (shaderTiles ? tiled : untiled) += 1;
            }
    }
    // Both sides of every condition were reached.
    EXPECT_GT(tiled, 0);
    EXPECT_GT(untiled, 0);
}

// --- docs/roofline.md -------------------------------------------------------

std::string fixed(double v, int digits) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// The default configuration of each screen-space kernel and of one SDF
// kernel (the six share one cost), full and (where it exists) half
// resolution, and the fast kernels' half resolution with the fused tail, at
// 1920x1080 on the H200's table entry, every pass compute in its declared
// workgroup, one dispatch: one row per distinct pass (kernel and size),
// naming the pipelines it is part of, with its launch term on each API.
std::string floorTable() {
    const DeviceFloor d = deviceFloor(device("NVIDIA H200"), std::nullopt);
    struct Row { std::string pass, kernel; double pixels; PassFloor floor, gl; std::vector<std::string> in; };
    std::vector<Row> rows;
    int pipelines = 0;
    for (const std::string kernel : {"alchemy", "hemisphere", "hemisphere_cosine", "ssdo", "sdf_classic", "alchemy_fast",
                                     "hemisphere_fast", "ssdo_fast"})
        for (const int variant : {0, 1, 2}) {   // full, half, half with the fused tail
            const bool half = variant > 0, fast = kernel.ends_with("_fast");
            if ((half && !supportsHalf(kernel)) || (variant == 2 && !fast)) continue;
            RunConfig c;
            c.kernel = kernel;
            c.width = 1920;
            c.height = 1080;
            c.half = half;
            if (variant == 2) c.params["fused_tail"] = 1;
            const std::string name = kernel + (variant == 1 ? " half" : variant == 2 ? " half fused" : "");
            ++pipelines;
            for (const PassSpec& p : buildPasses(c)) {
                const int w = p.half ? (c.width + 1) / 2 : c.width, h = p.half ? (c.height + 1) / 2 : c.height;
                const double pixels = double(w) * h;
                const auto* k = kernels::find(p.kernel);
                if (!k) return "no kernel " + p.kernel;
                const kernels::PassShape shape{true, k->workgroup, 1,
                                               (long long)k->workgroup.groupsX(w) * k->workgroup.groupsY(h)};
                const PassFloorResult r = passFloor(d, p.kernel, c.params, pixels, shape, gpu::Api::Vulkan);
                const PassFloorResult gl = passFloor(d, p.kernel, c.params, pixels, shape, gpu::Api::OpenGL);
                if (!r.floor || !gl.floor) return "no floor for " + configId(c) + " " + p.name + ": " + r.reason;
                auto it = std::find_if(rows.begin(), rows.end(),
                                       [&](const Row& x) { return x.pass == p.name && x.kernel == p.kernel && x.pixels == pixels; });
                if (it == rows.end()) it = rows.insert(rows.end(), Row{p.name, p.kernel, pixels, *r.floor, *gl.floor, {}});
                it->in.push_back(name);
            }
        }
    std::string out = "| pass | kernel | pixels | fetches / px | slots / px | DRAM bytes / px | fetch floor | "
                      "DRAM floor | launch vk / gl | floor vk / gl | bound | in |\n"
                      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |\n";
    for (const Row& r : rows) {
        std::string in;
        for (const auto& x : r.in) in += (in.empty() ? "" : ", ") + x;
        if (int(r.in.size()) == pipelines) in = "every pipeline";
        const PassFloor& f = r.floor;
        out += "| " + r.pass + " | `" + r.kernel + "` | " + fixed(r.pixels, 0) + " | " + number(f.cost.fetchesPerPixel) +
               " | " + number(f.cost.fetchSlotsPerPixel) + " | " + number(f.cost.dramBytesPerPixel) + " | " +
               fixed(f.fetchMs, 4) + " ms | " + fixed(f.dramMs, 4) + " ms | " + fixed(f.launchMs, 4) + " / " +
               fixed(r.gl.launchMs, 4) + " ms | **" + fixed(f.ms(), 4) + " / " + fixed(r.gl.ms(), 4) + " ms** | " +
               f.bound() + " | " + in + " |\n";
    }
    return out;
}

TEST(Roofline, RooflineDocumentHoldsTheComputedTable) {
    const std::string path = std::string(CAVITY_SOURCE_DIR) + "/docs/roofline.md";
    std::ifstream f(path);
    ASSERT_TRUE(f) << path;
    std::stringstream text;
    text << f.rdbuf();
    const std::string doc = text.str();
    const std::string begin = "<!-- floor table: tests/test_roofline.cpp writes it -->\n", end = "<!-- end floor table -->";
    const auto b = doc.find(begin), e = doc.find(end);
    ASSERT_NE(b, std::string::npos) << path << " lacks " << begin;
    ASSERT_NE(e, std::string::npos) << path << " lacks " << end;
    const std::string table = floorTable();
    EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), table)
        << path << ": the floor table is not what the code computes; put this between the markers:\n" << table;
}

}  // namespace
}  // namespace cavity
