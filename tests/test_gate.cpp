// The gate as a reviewer relies on it: it catches planted bugs and names the
// configuration, passes an unchanged build (twice, on both APIs), reports
// bad baselines and manifests as bad input, and its HTML report opens.
#include "blur_weights.h"
#include "gate/gate.h"
#include "report/gate_report.h"
#include "pipeline/config_id.h"
#include "gpu_fixture.h"
#include "chromium.h"
#include "run_binary.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <functional>
#include <set>

namespace cavity::test {
namespace {

namespace fs = std::filesystem;

const std::string kBaselines = std::string(CAVITY_SOURCE_DIR) + "/baselines";

fs::path tempDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("cavity-gate-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(d);
    return d;
}

gate::GateRun runOrDie(gate::GateOptions o) {
    auto r = gate::runGate(o);
    EXPECT_TRUE(r) << (r ? "" : r.error().message);
    return r ? *r : gate::GateRun{};
}

std::set<std::string> failing(const gate::GateRun& run) {
    std::set<std::string> ids;
    for (const auto& r : run.results)
        if (!r.passed()) ids.insert(r.id);
    return ids;
}

bool bothBackends(std::string* why) {
    return sharedBackend(gpu::Api::OpenGL, why) && sharedBackend(gpu::Api::Vulkan, why);
}

#define REQUIRE_BACKENDS()                                                    \
    do {                                                                      \
        std::string why;                                                      \
        if (!bothBackends(&why)) {                                            \
            if (inCI()) FAIL() << "CI=true requires both backends: " << why;  \
            GTEST_SKIP() << why;                                              \
        }                                                                     \
    } while (0)

// A planted defect: a source edit (file, text to find, replacement) or a
// swap of a declaration's derive function; the gate must fail `expect`.
struct Defect {
    std::string name;
    std::string file, find, replace;
    std::string kernel;                 // derive swap
    kernels::DeriveFn derive;
    std::string filter;                 // configurations to run
    std::string expect;                 // an id that must fail
};

std::vector<Defect> defects() {
    // The blur weights normalised by sum instead of 2·sum − w0: every tap but
    // the centre counts twice, so the kernel sums to more than one.
    kernels::DeriveFn sumNormalised = [](const kernels::ParamValues& v, std::map<std::string, std::vector<float>>& a) {
        const int r = int(std::lround(v.at("blur")));
        std::vector<float> w;
        if (r > 0) {
            const float s = float(r) / 2.0f;
            float sum = 0;
            for (int i = 0; i <= r; ++i) {
                w.push_back(std::exp(-0.5f * float(i * i) / (s * s)));
                sum += w.back();
            }
            for (auto& x : w) x /= sum;
        } else {
            w = {1.0f};
        }
        a["weights"] = w;
    };
    const std::string alchemy = "^corner/alchemy/n16/b4/full/160x90/vk/compute$";
    const std::string expect = "corner/alchemy/n16/b4/full/160x90/vk/compute";
    return {
        {"blur normalised by sum", "", "", "", "blur_bilateral", sumNormalised, alchemy, expect},
        {"bias sign flipped", "ao/alchemy/ssao_alchemy.glsl", "- P.bias", "+ P.bias", "", {}, alchemy, expect},
        {"sample count off by one", "ao/alchemy/ssao_alchemy.glsl", "int n = P.samples;", "int n = P.samples + 1;", "", {}, alchemy, expect},
        {"near clamp c = R", "ao/alchemy/ssao_alchemy.glsl", "float c = 0.1 * R;", "float c = R;", "", {}, alchemy, expect},
        {"range check removed", "ao/hemisphere/ssao_hemisphere.glsl",
         "if (P.range_check != 0) rangeWeight = smoothstep(0.0, 1.0, P.radius / max(abs(p.z - q.z), 1e-6));", "",
         "", {}, "^corner/hemisphere/n16/b4/full/160x90/vk/compute$", "corner/hemisphere/n16/b4/full/160x90/vk/compute"},
        {"half-resolution upsample offset by one texel", "include/upsample.glsl", "ivec2 base = ivec2(floor(c));",
         "ivec2 base = ivec2(floor(c)) + ivec2(1, 0);", "", {}, "^corner/alchemy/n16/b4/half/160x90/vk/compute$",
         "corner/alchemy/n16/b4/half/160x90/vk/compute"},
    };
}

class PlantedBug : public ::testing::TestWithParam<size_t> {};

TEST_P(PlantedBug, GateFailsAndNamesTheConfiguration) {
    REQUIRE_BACKENDS();
    const Defect d = defects()[GetParam()];
    gate::GateOptions o;
    o.baselines = kBaselines;
    o.out = tempDir("planted" + std::to_string(GetParam())).string();
    o.filter = d.filter;
    // One defect is rendered again (a real regression fails every attempt,
    // never reads as flaky); the others once, to keep CI short.
    o.retries = GetParam() == 0 ? 1 : 0;
    auto& registry = kernels::registryForTests();
    kernels::DeriveFn saved;
    kernels::KernelDecl* swapped = nullptr;
    if (!d.file.empty()) {
        const std::string* text = kernels::sourceFile(d.file);
        ASSERT_NE(text, nullptr) << d.file;
        const auto at = text->find(d.find);
        // The defect must really be planted, or this test proves nothing.
        ASSERT_NE(at, std::string::npos) << d.name << ": '" << d.find << "' not in kernels/" << d.file;
        std::string broken = *text;
        broken.replace(at, d.find.size(), d.replace);
        o.overrides[d.file] = broken;
    } else {
        for (auto& k : registry)
            if (k.name == d.kernel) swapped = &k;
        ASSERT_NE(swapped, nullptr);
        saved = swapped->derive;
        swapped->derive = d.derive;
    }
    const auto run = runOrDie(o);
    if (swapped) swapped->derive = saved;
    EXPECT_EQ(run.exitCode(), 1) << d.name;
    const auto ids = failing(run);
    EXPECT_TRUE(ids.count(d.expect)) << d.name << ": the gate did not fail " << d.expect;
    for (const auto& r : run.results)
        if (!r.passed()) {
            EXPECT_EQ(r.verdict(), "fail") << r.id;
            // A deterministic render that failed on images would fail again
            // bit for bit: not retried. Only the rest gets its retries.
            EXPECT_EQ(r.attempts, !r.imagesPassed() && r.deterministic ? 1 : 1 + o.retries) << r.id;
        }
    fs::remove_all(o.out);
}

INSTANTIATE_TEST_SUITE_P(Defects, PlantedBug, ::testing::Range<size_t>(0, defects().size()),
                         [](const auto& info) {
                             std::string n = defects()[info.param].name;
                             for (auto& ch : n)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return n;
                         });

// A NaN written anywhere fails the configuration and is named where it was
// produced, even where no checked image shows it: the composite is 8-bit and
// clamps it away, and a blur's max() may squash it.
struct PlantedNaN {
    std::string name, file, find, replace;
    std::string pass, image;   // what the failure must name
};

std::vector<PlantedNaN> plantedNaNs() {
    // A quiet NaN at one pixel, from its bit pattern.
    return {
        {"normal", "passes/gbuffer_sdf/gbuffer_sdf.glsl", "write_normal(pixel, vec4(dot(n, right), dot(n, up), -dot(n, forward), 0.0));",
         "write_normal(pixel, vec4(dot(n, right), dot(n, up), -dot(n, forward), 0.0) * (pixel == ivec2(37, 21) ? "
         "uintBitsToFloat(0x7fc00000u) : 1.0));",
         "gbuffer", "normal"},
        {"raw_ao", "ao/alchemy/ssao_alchemy.glsl", "write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));",
         "write_ao(pixel, vec4(pixel == ivec2(37, 21) ? uintBitsToFloat(0x7fc00000u) : A, 0.0, 0.0, 0.0));", "ao", "ao"},
    };
}

class PlantedNonFinite : public ::testing::TestWithParam<size_t> {};

TEST_P(PlantedNonFinite, FailsTheGateNamingThePassAndImage) {
    REQUIRE_BACKENDS();
    const PlantedNaN d = plantedNaNs()[GetParam()];
    const std::string* text = kernels::sourceFile(d.file);
    ASSERT_NE(text, nullptr) << d.file;
    const auto at = text->find(d.find);
    ASSERT_NE(at, std::string::npos) << d.name << ": '" << d.find << "' not in kernels/" << d.file;
    std::string broken = *text;
    broken.replace(at, d.find.size(), d.replace);
    gate::GateOptions o;
    o.baselines = kBaselines;
    o.out = tempDir("nan" + std::to_string(GetParam())).string();
    o.filter = "^corner/alchemy/n16/b4/full/160x90/(gl|vk)/compute$";
    o.overrides[d.file] = broken;
    const auto run = runOrDie(o);
    EXPECT_EQ(run.exitCode(), 1) << d.name;
    ASSERT_EQ(run.results.size(), 2u);
    for (const auto& r : run.results) {
        EXPECT_FALSE(r.passed()) << r.id;
        EXPECT_EQ(r.errorCode, 1) << r.id;
        const std::string expect = "pass " + d.pass + " wrote 1 pixel of NaN or infinity to " + d.image + " (first at pixel 37,21)";
        EXPECT_NE(r.error.find(expect), std::string::npos) << r.id << ": " << r.error;
    }
    fs::remove_all(o.out);
}

INSTANTIATE_TEST_SUITE_P(Planted, PlantedNonFinite, ::testing::Range<size_t>(0, plantedNaNs().size()),
                         [](const auto& info) { return plantedNaNs()[info.param].name; });

// The composite's dither removed moves every other pixel by one 8-bit step:
// too little for the means, SSIM or FLIP to see with a margin, but half the
// pixels differ, far over the differing-pixel tolerance.
TEST(Gate, DitherRemovedFailsOnDifferingPixelsWithAMargin) {
    REQUIRE_BACKENDS();
    const std::string find = "if (P.dither != 0) {";
    std::string broken = *kernels::sourceFile("include/composite.glsl");
    ASSERT_NE(broken.find(find), std::string::npos);
    broken.replace(broken.find(find), find.size(), "if (P.dither == 2) {");
    gate::GateOptions o;
    o.baselines = kBaselines;
    o.out = tempDir("dither").string();
    o.filter = "^corner/alchemy/n16/b4/full/160x90/vk/compute$";
    o.overrides["include/composite.glsl"] = broken;
    const auto run = runOrDie(o);
    ASSERT_EQ(run.results.size(), 1u);
    EXPECT_EQ(run.exitCode(), 1);
    bool seen = false;
    for (const auto& i : run.results[0].images) {
        if (i.image != "color") continue;
        seen = true;
        ASSERT_TRUE(i.metrics);
        EXPECT_EQ(i.metrics->channelsCompared, 3) << "the constant alpha is not a colour channel";
        EXPECT_GT(i.metrics->differingShare, 10 * i.tolerance.differingShareMax);
        EXPECT_TRUE(std::any_of(i.failures.begin(), i.failures.end(),
                                [](const std::string& f) { return f.find("differ by more than 0 steps") != std::string::npos; }))
            << ::testing::PrintToString(i.failures);
    }
    EXPECT_TRUE(seen);
    fs::remove_all(o.out);
}

// A device entry of scope "all" applies against the device's own class's
// references too; one of the default scope only against the stored
// baselines. The stored manifest holds the CPU renderers to their own
// noise on every route, tighter than the cross-device defaults.
TEST(Gate, DeviceToleranceScopeDecidesWhichReferencesItApplies) {
    const fs::path dir = tempDir("scope");
    fs::create_directories(dir);
    std::ofstream(dir / "manifest.json") << R"({"pipelines": {"*": {"rmse": 0.003, "max_abs": 0.1}},
        "devices": [{"pattern": "NVIDIA", "pipelines": {"*": {"max_abs": 0.5}}},
                    {"pattern": "llvmpipe", "scope": "all", "pipelines": {"*": {"rmse": 0.0016}}}]})";
    const auto m = gate::loadManifest((dir / "manifest.json").string());
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_EQ(m->forPipeline("alchemy", "NVIDIA H100 80GB HBM3", false).maxAbs, 0.5);
    EXPECT_EQ(m->forPipeline("alchemy", "NVIDIA H100 80GB HBM3", true).maxAbs, 0.1);
    EXPECT_EQ(m->forPipeline("alchemy", "llvmpipe (LLVM 15.0.6, 256 bits)", false).rmse, 0.0016);
    EXPECT_EQ(m->forPipeline("alchemy", "llvmpipe (LLVM 15.0.6, 256 bits)", true).rmse, 0.0016);
    EXPECT_EQ(m->forPipeline("alchemy", "", true).rmse, 0.003);
    // Sized tolerances: stated for 14400 pixels, an image of four times as
    // many gets a quarter of the mean and share and half the RMSE; sizing
    // twice for one image is sizing once; unsized ones hold at any size.
    gate::Tolerance sized;
    sized.meanAbs = 6e-5;
    sized.rmse = 0.002;
    sized.overThresholdShare = 5e-4;
    sized.sizedForPixels = 14400;
    const auto big = gate::sizedFor(sized, 320 * 180);
    EXPECT_DOUBLE_EQ(big.meanAbs, 1.5e-5);
    EXPECT_DOUBLE_EQ(big.rmse, 0.001);
    EXPECT_DOUBLE_EQ(big.overThresholdShare, 1.25e-4);
    EXPECT_DOUBLE_EQ(gate::sizedFor(big, 320 * 180).meanAbs, big.meanAbs);
    EXPECT_DOUBLE_EQ(gate::sizedFor(sized, 24 * 12).overThresholdShare, 0.025);
    EXPECT_EQ(gate::sizedFor(m->forPipeline("alchemy", "NVIDIA H100"), 320 * 180).rmse, 0.003);
    const auto stored = gate::loadManifest(kBaselines + "/manifest.json");
    ASSERT_TRUE(stored.ok()) << stored.error().message;
    for (const bool own : {false, true}) {
        const auto cpu = stored->forPipeline("alchemy", "llvmpipe (LLVM 15.0.6, 256 bits)", own);
        const auto any = stored->forPipeline("alchemy", "", own);
        EXPECT_LT(cpu.meanAbs, any.meanAbs);
        EXPECT_LT(cpu.rmse, any.rmse);
        EXPECT_LT(cpu.overThresholdShare, any.overThresholdShare);
    }
    fs::remove_all(dir);
}

// A change within tolerance passes and is reported as changed, never as
// unchanged: one pixel of the composite two 8-bit steps redder.
TEST(Gate, AChangeWithinToleranceIsReportedAsChanged) {
    REQUIRE_BACKENDS();
    gate::GateOptions o;
    o.baselines = kBaselines;
    o.out = tempDir("changed").string();
    o.filter = "^corner/alchemy/n16/b4/full/160x90/vk/compute$";
    o.retries = 0;
    std::string composite = *kernels::sourceFile("passes/composite/composite.glsl");
    const std::string write = "write_color(pixel, compositeColor(pixel, albedo, N, ao));";
    ASSERT_NE(composite.find(write), std::string::npos);
    composite.replace(composite.find(write), write.size(),
                      "vec4 c = compositeColor(pixel, albedo, N, ao);\n"
                      "    if (pixel == ivec2(40, 40)) c.r = c.r > 0.5 ? c.r - 2.0 / 255.0 : c.r + 2.0 / 255.0;\n"
                      "    write_color(pixel, c);");
    o.overrides["passes/composite/composite.glsl"] = composite;
    const auto run = runOrDie(o);
    ASSERT_EQ(run.results.size(), 1u);
    EXPECT_EQ(run.exitCode(), 0) << report::summaryMarkdown(run);
    const auto& r = run.results[0];
    EXPECT_EQ(r.verdict(), "changed") << report::summaryMarkdown(run);
    for (const auto& i : r.images)
        if (i.image == "color") {
            EXPECT_EQ(i.route, "tolerance");
            EXPECT_TRUE(i.changed());
            // Its reference and heat-map are written, as for a failure: the
            // card (and --strict's failure of it) shows what changed, not
            // "baseline missing".
            EXPECT_TRUE(fs::is_regular_file(i.baselinePng)) << "'" << i.baselinePng << "'";
            EXPECT_TRUE(fs::is_regular_file(i.diffPng)) << "'" << i.diffPng << "'";
        }
    const std::string summary = report::summaryMarkdown(run);
    EXPECT_NE(summary.find("changed within tolerance"), std::string::npos) << summary;
    EXPECT_NE(report::commitStatus(run, "")["description"].get<std::string>().find("1 changed within tolerance"),
              std::string::npos);
    // --strict: the same change fails the run (Mesa's trace-checksum policy)
    // in every report, and survives gate.json.
    gate::GateRun strict = run;
    strict.strict = true;
    strict.applyStrict();
    EXPECT_EQ(strict.exitCode(), 1);
    EXPECT_EQ(report::commitStatus(strict, "")["state"], "failure");
    EXPECT_NE(report::commitStatus(strict, "")["description"].get<std::string>().find("1 of 1 configurations failed"),
              std::string::npos) << report::commitStatus(strict, "").dump();
    const std::string strictSummary = report::summaryMarkdown(strict);
    EXPECT_NE(strictSummary.find("**1 of 1 configurations failed**"), std::string::npos) << strictSummary;
    EXPECT_NE(strictSummary.find("--strict"), std::string::npos) << strictSummary;
    const std::string junit = report::junitXml(strict);
    EXPECT_NE(junit.find("failures=\"1\""), std::string::npos) << junit;
    const auto json = gate::toJson(strict);
    EXPECT_TRUE(json["results"][0]["fatal"].get<bool>()) << json.dump();
    const auto back = gate::fromJson(json, "gate.json");
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(back->exitCode(), 1);
    fs::remove_all(o.out);
}

// The colour is 8-bit: a readback and the PNG reader may turn the same step
// into floats a last bit apart, which must not read as a change (a baseline
// accepted from this very render would then fail --strict). A whole step
// does; the float images change at any difference.
TEST(Gate, ChangedMeansAWholeStepForTheEightBitColour) {
    const auto check = [](const std::string& image, double maxAbs) {
        gate::ImageCheck i;
        i.image = image;
        i.metrics = metrics::Report{};
        i.metrics->maxAbs = maxAbs;
        return i.changed();
    };
    EXPECT_FALSE(check("color", 0.0));
    EXPECT_FALSE(check("color", 6e-8));
    EXPECT_TRUE(check("color", 1.0 / 255.0));
    EXPECT_TRUE(check("ao", 6e-8));
    EXPECT_TRUE(check("ao_blur", 6e-8));
    EXPECT_FALSE(check("ao", 0.0));
}

TEST(Gate, UnchangedBuildPassesTwiceOnBothApis) {
    REQUIRE_BACKENDS();
    for (int round = 0; round < 2; ++round) {
        gate::GateOptions o;
        o.baselines = kBaselines;
        o.out = tempDir("clean" + std::to_string(round)).string();
        // The whole matrix once; the second run, which asks only that a
        // render again in the same process judges alike, on one scene.
        if (round == 1) o.filter = "^corner/alchemy";
        const auto run = runOrDie(o);
        EXPECT_EQ(run.exitCode(), 0) << "round " << round << "\n" << report::summaryMarkdown(run);
        std::set<std::string> apis;
        for (const auto& r : run.results) {
            apis.insert(r.id.substr(r.id.rfind('/', r.id.rfind('/') - 1) + 1, 2));
            EXPECT_TRUE(r.deterministic) << r.id;
        }
        EXPECT_EQ(apis, (std::set<std::string>{"gl", "vk"}));
        // Unchanged means every image as approved: on a CPU renderer whose
        // digests baselines/approvals.json records (one approved image of
        // the run shows it is that renderer), no configuration may read
        // changed. Another CPU's renderer rounds otherwise: it reports its
        // images as changed within tolerance, and passes.
        int digestRoute = 0, changed = 0;
        for (const auto& r : run.results) {
            for (const auto& i : r.images) digestRoute += i.route == "digest";
            changed += r.verdict() == "changed";
        }
        if (digestRoute > 0) {
            EXPECT_EQ(changed, 0) << "round " << round << "\n" << report::summaryMarkdown(run);
        } else {
            std::printf("no image of this renderer is approved: %d configurations read changed\n", changed);
        }
        fs::remove_all(o.out);
    }
}

TEST(Gate, ShardsPartitionTheMatrix) {
    std::set<size_t> seen;
    for (int shard = 0; shard < 3; ++shard)
        for (size_t i = 0; i < 20; ++i)
            if (plan::inShard(i, shard, 3)) {
                EXPECT_TRUE(seen.insert(i).second) << i;
            }
    EXPECT_EQ(seen.size(), 20u);
}

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// The page's data is gate.json as written beside it, inlined so that no text
// in it can end its <script> block or change how the block parses: a
// message holding "</script>" or "<!--<script>" stays data, and the page
// shows it as text.
TEST(Gate, HtmlReportInlinesGateJsonThatNoMessageBreaksOutOf) {
    gate::GateRun run;
    run.matrix = "ci";
    gate::ConfigResult r;
    r.id = "corner/alchemy/n16/b4/full/160x90/vk/compute";
    r.error = "</script><!--<script> a & b </SCRIPT>";
    r.errorCode = 4;
    run.results.push_back(r);
    const fs::path out = tempDir("inline");
    ASSERT_TRUE(report::writeReports(run, out.string()).ok());
    const std::string html = slurp(out / "index.html");
    const std::string open = "<script type=\"application/json\" id=\"gate-data\">";
    const auto at = html.find(open);
    ASSERT_NE(at, std::string::npos);
    const std::string block = html.substr(at + open.size(), html.find("</script>", at) - at - open.size());
    EXPECT_EQ(block.find('<'), std::string::npos) << block;
    const auto data = nlohmann::json::parse(block);
    EXPECT_EQ(data["gate"], nlohmann::json::parse(slurp(out / "gate.json")));
    EXPECT_EQ(data["view"]["order"], nlohmann::json::array({0}));
    REQUIRE_CHROMIUM();
    const std::string dom = renderedDom(out / "index.html");
    EXPECT_NE(dom.find("<p class=\"bad\">&lt;/script&gt;&lt;!--&lt;script&gt; a &amp; b &lt;/SCRIPT&gt;</p>"), std::string::npos)
        << dom;
    EXPECT_NE(dom.find("<title>Cavity gate ci: 1 failed</title>"), std::string::npos);
    fs::remove_all(out);
}

// A failing result of `maxAbs` on one image against a tolerance of 0.02.
gate::ConfigResult failingResult(gpu::Api api, int samples, double maxAbs) {
    gate::ConfigResult r;
    r.config.api = api;
    r.config.params["samples"] = samples;
    r.id = pipeline::configId(r.config);
    gate::ImageCheck i;
    i.image = "ao";
    metrics::Report m{};
    m.maxAbs = maxAbs;
    m.ssim = 1;
    m.psnr = 60;
    i.metrics = m;
    i.failures = {"max abs error " + std::to_string(maxAbs) + " > 0.02"};
    r.images.push_back(i);
    return r;
}

// The page lists failures worst first (by how far past its tolerance each
// is), and a failure that is the same on both APIs is one card naming both.
TEST(Gate, HtmlReportPutsTheWorstFailureFirstAndSharesEqualCards) {
    gate::GateRun run;
    run.matrix = "ci";
    run.results.push_back(failingResult(gpu::Api::OpenGL, 16, 0.03));
    run.results.push_back(failingResult(gpu::Api::Vulkan, 16, 0.03));
    run.results.push_back(failingResult(gpu::Api::Vulkan, 32, 0.5));
    run.results.push_back(failingResult(gpu::Api::OpenGL, 32, 0.25));
    const auto data = report::reportData(run, "");
    EXPECT_EQ(data["view"]["order"], nlohmann::json::array({2, 3, 0})) << data["view"]["order"];
    EXPECT_EQ(data["view"]["results"][1]["card"], 0);
    EXPECT_EQ(data["view"]["results"][0]["same"], nlohmann::json::array({run.results[1].label()}));
    EXPECT_EQ(data["view"]["results"][3]["same"], nlohmann::json::array());
    // The shared card's commands select both APIs.
    std::string both = run.results[0].id;
    both.replace(both.find("/gl/"), 4, "/(gl|vk)/");
    EXPECT_NE(data["view"]["results"][0]["note"].get<std::string>().find("--filter '^" + both + "$'"), std::string::npos)
        << data["view"]["results"][0]["note"];
    REQUIRE_CHROMIUM();
    const fs::path out = tempDir("shared-cards");
    ASSERT_TRUE(report::writeReports(run, out.string()).ok());
    const std::string dom = renderedDom(out / "index.html");
    const std::string text = dom.substr(0, dom.find("<script"));
    EXPECT_EQ(text.find("data-id=\"" + run.results[1].id + "\""), std::string::npos) << "shown in the OpenGL card";
    EXPECT_NE(text.find("every metric within 1%, on <code>" + run.results[1].label() + "</code>"), std::string::npos);
    EXPECT_LT(text.find("data-id=\"" + run.results[2].id + "\""), text.find("data-id=\"" + run.results[3].id + "\""));
    EXPECT_LT(text.find("data-id=\"" + run.results[3].id + "\""), text.find("data-id=\"" + run.results[0].id + "\""));
    fs::remove_all(out);
}

// The report a reviewer opens: every configuration present, failing first,
// loadable by headless Chromium from disk; the screenshot is kept to look at.
TEST(Gate, HtmlReportOpensInHeadlessChromiumWithFailuresFirst) {
    REQUIRE_BACKENDS();
    REQUIRE_CHROMIUM();
    gate::GateOptions o;
    o.baselines = kBaselines;
    o.out = tempDir("report").string();
    o.matrix = "ci";
    o.filter = "^corner/.*/vk/";
    o.retries = 0;
    const Defect d = defects()[1];   // bias sign flipped: alchemy fails
    std::string broken = *kernels::sourceFile(d.file);
    broken.replace(broken.find(d.find), d.find.size(), d.replace);
    o.overrides[d.file] = broken;
    const auto run = runOrDie(o);
    ASSERT_TRUE(report::writeReports(run, o.out).ok());
    const fs::path html = fs::path(o.out) / "index.html";
    const fs::path shot = fs::path(CAVITY_BINARY_DIR) / "gate_report_screenshot.png";
    ASSERT_EQ(runBinary("timeout", kChromium + "--screenshot=" + shot.string() + " file://" + html.string()).code, 0);
    EXPECT_GT(fs::file_size(shot), 10000u);
    // What the page's script built from the inlined data: the document up to
    // the script itself (the data block and report.js follow the results).
    const std::string page = renderedDom(html);
    const std::string text = page.substr(0, page.find("<script"));
    size_t lastFail = 0, firstPass = std::string::npos;
    for (const auto& r : run.results) {
        const auto at = text.find("data-id=\"" + r.id + "\"");
        ASSERT_NE(at, std::string::npos) << r.id << " missing from the report";
        if (r.passed()) firstPass = std::min(firstPass, at);
        else lastFail = std::max(lastFail, at);
    }
    EXPECT_FALSE(failing(run).empty());
    EXPECT_LT(lastFail, firstPass) << "failing configurations must come first";
    // The overview grid before the cards: one cell a configuration, coloured
    // by its verdict, linking to its card.
    const std::regex cell("<a class=\"cell (pass|fail|noted|error)\" href=\"#cfg[0-9]+\"");
    size_t cells = 0, failCells = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), cell); it != std::sregex_iterator(); ++it) {
        ++cells;
        failCells += (*it)[1] == "fail";
    }
    EXPECT_EQ(cells, run.results.size());
    EXPECT_EQ(failCells, failing(run).size());
    EXPECT_LT(text.find("class=\"grid\""), text.find("class=\"cfg "));
    // JUnit as GitLab and Jenkins read it: failure text in the element body,
    // every time in seconds with three decimals, a time on every testcase.
    std::ifstream j(fs::path(o.out) / "junit.xml");
    const std::string junit((std::istreambuf_iterator<char>(j)), std::istreambuf_iterator<char>());
    const std::regex timeAttr("time=\"([^\"]*)\""), threeDecimals("[0-9]+\\.[0-9]{3}");
    int times = 0;
    for (auto it = std::sregex_iterator(junit.begin(), junit.end(), timeAttr); it != std::sregex_iterator(); ++it, ++times)
        EXPECT_TRUE(std::regex_match((*it)[1].str(), threeDecimals)) << (*it)[1].str();
    size_t testcases = 0;
    for (size_t at = junit.find("<testcase "); at != std::string::npos; at = junit.find("<testcase ", at + 1)) ++testcases;
    EXPECT_EQ(size_t(times), testcases + 2) << "a time on every testcase, the suite and the suites";
    EXPECT_TRUE(std::regex_search(junit, std::regex("<failure message=\"[^\"]+\" type=\"failure\">[^<]+</failure>")))
        << "failure text belongs in the element body";
    // The summary fills its tolerance column; a failing image's heat-map has
    // its colour scale; a passing configuration shows thumbnails, not the
    // baseline, diff and slider.
    std::ifstream sm(fs::path(o.out) / "summary.md");
    const std::string summary((std::istreambuf_iterator<char>(sm)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(std::regex_search(summary, std::regex("\\| mean abs error \\([a-z_, ]*\\) \\| [0-9]+ \\(vk\\) \\| mean abs error [0-9.]+ at `[^`]+` \\| ≤ [0-9.e+-]+( \\([0-9.e+-]+ to [0-9.e+-]+ across them\\))? \\|")))
        << summary;
    EXPECT_NE(text.find("class=\"scale\""), std::string::npos);
    for (const auto& r : run.results) {
        if (!r.passed()) continue;
        const auto at = text.find("data-id=\"" + r.id + "\""), next = text.find("data-id=", at + 1);
        const std::string block = text.substr(at, next == std::string::npos ? std::string::npos : next - at);
        EXPECT_NE(block.find("class=\"thumb\""), std::string::npos) << r.id;
        EXPECT_EQ(block.find("slider"), std::string::npos) << r.id << " passed but shows the full comparison";
    }
    // The title as the browser parsed it (a raw-string delimiter once leaked into it).
    const auto t0 = text.find("<title>"), t1 = text.find("</title>");
    ASSERT_NE(t0, std::string::npos);
    EXPECT_EQ(text.substr(t0 + 7, t1 - t0 - 7), "Cavity gate ci: " + std::to_string(failing(run).size()) + " failed");
    fs::remove_all(o.out);
}

}  // namespace
}  // namespace cavity::test
