// The cavity command as a user meets it: exit codes, one-line errors that
// name the flag, the value and what is allowed, and nothing written on bad input.
#include "run_binary.h"
#include "kernel.h"
#include "plan/sweep.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <regex>
#include <string>

namespace fs = std::filesystem;

namespace {

using ::cavity::test::Outcome;

// `redirect`: how the shell sends the two streams into the pipe read here.
Outcome cavity(const std::string& args, const std::string& env = "", const std::string& redirect = "2>&1") {
    return ::cavity::test::runBinary(CAVITY_EXE, args, env, redirect);
}

// The kernels --kernel accepts as the registry lists them, the way the
// message names them: the AO kernels, then the ground truth (role
// "reference", declared last).
std::string aoList() {
    std::string s;
    for (const auto& k : cavity::plan::aoKernels()) s += (s.empty() ? "" : ", ") + k;
    for (const auto& k : cavity::kernels::all())
        if (k.role == cavity::kernels::Role::Reference) s += ", " + k.name;
    return s;
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("cavity-cli-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

struct BadCase {
    std::string args;
    std::string message;   // the one line expected on stderr
};

// Every command, and every command group before its subcommand, answers
// --help on stdout with exit 0 (a group lists its subcommands).
TEST_F(Cli, EveryCommandAndGroupAnswersHelp) {
    for (const std::string c : {"run", "gate", "gate judge", "gate merge", "baselines", "baselines update",
                                "baselines approve", "store", "store check", "compare", "ab", "quality", "history",
                                "kernels", "kernels list", "kernels show", "kernels check"}) {
        const Outcome o = cavity(c + " --help", "", "2>/dev/null");
        EXPECT_EQ(o.code, 0) << c;
        EXPECT_NE(o.output.find("sage: cavity " + c.substr(0, c.find(' '))), std::string::npos) << c << ": " << o.output;
    }
}

TEST_F(Cli, BadInputExitsTwoWithOneLineAndWritesNothing) {
    const std::vector<BadCase> cases = {
        {"--backend metal", "cavity run: --backend metal: must be gl, vk or all"},
        {"--scene moon", "cavity run: --scene moon: must be one of corner, slats, open, contact, grille, plates"},
        {"--view 4", "cavity run: --view 4: must be an integer in 0..3"},
        {"--kernel sdf_classic --strength -1", "cavity run: --strength -1: must be a number in 0..100"},
        {"--kernel ground_truth --rays 512", "cavity run: --rays 512: must be an integer in 1024..65536"},
        {"--kernel ground_truth --rays many", "cavity run: --rays 'many': must be an integer in 1024..65536"},
        {"--kernel nope", "cavity run: --kernel nope: unknown kernel (have: " + aoList() +
                                 "; a package's: load it with --kernels DIR or CAVITY_KERNELS)"},
        {"--samples 0", "cavity run: --samples 0: must be an integer in 1..256"},
        {"--samples 257", "cavity run: --samples 257: must be an integer in 1..256"},
        {"--radius 0", "cavity run: --radius 0: must be a number > 0"},
        {"--radius -1", "cavity run: --radius -1: must be a number > 0"},
        {"--blur 33", "cavity run: --blur 33: must be an integer in 0..32"},
        {"--blur -1", "cavity run: --blur -1: must be an integer in 0..32"},
        {"--res 0x180", "cavity run: --res 0x180: must be WIDTHxHEIGHT with each in 1..16384"},
        {"--res 16385x10", "cavity run: --res 16385x10: must be WIDTHxHEIGHT with each in 1..16384"},
        {"--res wide", "cavity run: --res wide: must be WIDTHxHEIGHT with each in 1..16384"},
        {"--frames 0", "cavity run: --frames 0: must be an integer in 1..100000"},
        {"--bogus 1", "cavity run: --bogus: unknown flag (see cavity run --help)"},
    };
    for (const auto& c : cases) {
        const Outcome o = cavity("run " + c.args + " --out " + dir.string());
        EXPECT_EQ(o.code, 2) << c.args << "\n" << o.output;
        EXPECT_EQ(o.output.rfind(c.message, 0), 0u) << c.args << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << c.args << "\n" << o.output;
        EXPECT_FALSE(fs::exists(dir)) << c.args;
    }
}

TEST_F(Cli, QualityBadInputExitsTwoWithOneLine) {
    const std::vector<BadCase> cases = {
        {"--backend all", "cavity quality: --backend all: must be gl or vk"},
        {"--scene moon", "cavity quality: --scene moon: must be one of corner, slats, open, contact, grille, plates"},
        {"--kernel ground_truth", "cavity quality: --kernel ground_truth: not an AO kernel (see cavity run --help)"},
        {"--samples 0", "cavity quality: --samples 0: must be an integer in 1..256"},
        {"--rays 10", "cavity quality: --rays 10: must be an integer in 1024..65536"},
        {"--res 0x1", "cavity quality: --res 0x1: must be WIDTHxHEIGHT with each in 1..16384"},
        {"--resolution quarter", "cavity quality: --resolution quarter: must be full or half"},
        {"--nope 1", "cavity quality: --nope: unknown flag (see cavity quality --help)"},
        {"--interleave 8", "cavity quality: --interleave 8: must be an integer in 1..4"},
        {"--exact NaN", "cavity quality: --exact 'NaN': must be 0 or 1"},
    };
    for (const auto& c : cases) {
        const Outcome o = cavity("quality " + c.args + " --out " + dir.string());
        EXPECT_EQ(o.code, 2) << c.args << "\n" << o.output;
        EXPECT_EQ(o.output.rfind(c.message, 0), 0u) << c.args << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << c.args << "\n" << o.output;
        EXPECT_FALSE(fs::exists(dir)) << c.args;
    }
}

// A switch reaches exactly the kernels that declare it: the ids say so.
TEST_F(Cli, QualitySwitchesSetOnlyTheKernelsThatDeclareThem) {
    const Outcome o = cavity("quality --list --scene corner --samples 16 --kernel alchemy,alchemy_fast,hemisphere_fast "
                             "--interleave 4 --exact 1");
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_NE(o.output.find("corner/alchemy/n16/"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("alchemy/n16/exact"), std::string::npos) << o.output;
    for (const std::string k : {"alchemy_fast", "hemisphere_fast"})
        EXPECT_NE(o.output.find("corner/" + k + "/n16/b0/exact=1/interleave=4/full/"), std::string::npos) << o.output;
}

// --kernel-source measures an edited kernel: one that finds no occlusion
// anywhere reads AO 1 over every surface pixel, its error the truth's own
// darkening, and quality.json names the file it measured.
TEST_F(Cli, QualityMeasuresAnEditedKernel) {
    fs::create_directories(dir);
    const fs::path open = dir / "open.glsl";
    std::ofstream(open) << "#include \"include/common.glsl\"\n"
                           "void cavity_main(ivec2 pixel) {\n"
                           "    write_ao(pixel, vec4(1.0));\n"
                           "    write_ao_key(pixel, vec4(1.0, texelFetch(in_zmip, pixel, 0).r, 0.0, 0.0));\n}\n";
    const std::string args = "quality --kernel alchemy_fast --samples 16 --res 64x36 --scene corner --blur 4 --quiet --out ";
    const Outcome edited = cavity(args + (dir / "edited").string() + " --kernel-source ssao_alchemy_fast.glsl=" + open.string());
    ASSERT_EQ(edited.code, 0) << edited.output;
    const Outcome plain = cavity(args + (dir / "plain").string());
    ASSERT_EQ(plain.code, 0) << plain.output;
    std::ifstream fe(dir / "edited" / "quality.json"), fp(dir / "plain" / "quality.json");
    const auto e = nlohmann::json::parse(fe), p = nlohmann::json::parse(fp);
    EXPECT_EQ(e["rows"][0]["mean_ao"].get<double>(), 1.0);
    EXPECT_NEAR(e["rows"][0]["mae"].get<double>(), 1.0 - e["rows"][0]["mean_truth"].get<double>(), 1e-9);
    EXPECT_LT(p["rows"][0]["mean_ao"].get<double>(), 0.99);
    ASSERT_EQ(e["kernel_sources"].size(), 1u);
    EXPECT_EQ(e["kernel_sources"][0]["name"], "ao/alchemy_fast/ssao_alchemy_fast.glsl");
    EXPECT_TRUE(p["kernel_sources"].empty());
    // The edited row is labelled, with the committed kernel's MAE beside it.
    EXPECT_TRUE(e["rows"][0]["edited"].get<bool>());
    EXPECT_DOUBLE_EQ(e["rows"][0]["committed_mae"].get<double>(), p["rows"][0]["mae"].get<double>());
    EXPECT_FALSE(p["rows"][0]["edited"].get<bool>());
    EXPECT_NE(edited.output.find("alchemy_fast*"), std::string::npos) << edited.output;
    EXPECT_NE(edited.output.find("vs committed: its MAE minus the committed kernel's"), std::string::npos) << edited.output;
}

TEST_F(Cli, UnwritableOutputFolderExitsTwo) {
    fs::create_directories(dir);
    std::ofstream(dir / "file") << "x";
    const Outcome o = cavity("run --out " + (dir / "file" / "sub").string());
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find("--out"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("cannot be created"), std::string::npos) << o.output;
}

TEST_F(Cli, MissingBackendExitsThreeAndTheOtherStillRuns) {
    // No Vulkan ICD: the loader finds no driver.
    const Outcome o = cavity("run --backend all --res 64x36 --frames 2 --warmup 0 --out " + dir.string(),
                             "VK_DRIVER_FILES=/nonexistent.json VK_ICD_FILENAMES=/nonexistent.json");
    EXPECT_EQ(o.code, 3) << o.output;
    EXPECT_NE(o.output.find("vk: could not start"), std::string::npos) << o.output;
    std::ifstream f(dir / "results.json");
    ASSERT_TRUE(f) << o.output;
    const auto doc = nlohmann::json::parse(f);
    ASSERT_EQ(doc["runs"].size(), 1u);
    EXPECT_EQ(doc["runs"][0]["backend"], "gl");
    ASSERT_EQ(doc["errors"].size(), 1u);
    EXPECT_EQ(doc["errors"][0]["backend"], "vk");
    EXPECT_EQ(doc["errors"][0]["code"], 3);
}

TEST_F(Cli, RunWritesImagesAndResults) {
    const Outcome o = cavity("run --backend all --scene corner --kernel alchemy --samples 16 --blur 4 --res 160x90 "
                             "--frames 3 --warmup 1 --out " + dir.string());
    ASSERT_EQ(o.code, 0) << o.output;
    for (const char* api : {"gl", "vk"}) {
        const fs::path id = dir / "corner/alchemy/n16/b4/full/160x90" / api / "compute";
        for (const char* f : {"ao.exr", "ao.png", "ao_blur.exr", "ao_blur.png", "color.exr", "color.png"})
            EXPECT_TRUE(fs::exists(id / f)) << (id / f);
    }
    std::ifstream f(dir / "results.json");
    const auto doc = nlohmann::json::parse(f);
    EXPECT_EQ(doc["schema"], "cavity.results/1");
    ASSERT_EQ(doc["runs"].size(), 2u);
    for (const auto& r : doc["runs"]) {
        EXPECT_EQ(r["config"]["samples"], 16);
        EXPECT_EQ(r["frame"]["samples_ms"].size(), 3u);
        for (const auto& p : r["passes"]) EXPECT_GT(p["stats"]["median_ms"].get<double>(), 0.0);
    }
    // The summary names both APIs' kernel row; the long table is in table.txt.
    EXPECT_NE(o.output.find("alchemy"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("open " + (dir / "index.html").string()), std::string::npos) << o.output;
    std::ifstream table(dir / "table.txt");
    const std::string tableText{std::istreambuf_iterator<char>(table), std::istreambuf_iterator<char>()};
    EXPECT_NE(tableText.find("median ms"), std::string::npos);
    EXPECT_NE(tableText.find("pipeline"), std::string::npos);
}

// --max-time bounds a run whatever --frames asks for, and says so.
TEST_F(Cli, MaxTimeBoundsARunThatAsksForMoreFrames) {
    const Outcome o = cavity("run --backend vk --res 32x18 --frames 100000 --max-time 0.3 --quiet --out " + dir.string());
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_NE(o.output.find("--max-time stopped measuring after"), std::string::npos) << o.output;
    std::ifstream f(dir / "results.json");
    const auto doc = nlohmann::json::parse(f);
    ASSERT_EQ(doc["runs"].size(), 1u);
    EXPECT_EQ(doc["runs"][0]["timing"]["stop"], "time") << doc["runs"][0]["timing"];
    const size_t frames = doc["runs"][0]["frame"]["samples_ms"].size();
    EXPECT_GE(frames, 3u);
    EXPECT_LT(frames, 100000u);
}

// --views measures camera views in turn, as cavity_bench does, and keeps
// view 0's images: the same bytes as a run on one chain.
TEST_F(Cli, ViewsMeasuredInTurnKeepViewZerosImages) {
    std::string bytes[2][2];
    for (int views : {1, 4}) {
        const fs::path out = dir / ("views" + std::to_string(views));
        const Outcome o = cavity("run --backend vk --kernel alchemy_fast --res 64x36 --frames 8 --warmup 1 --quiet --views " +
                                 std::to_string(views) + " --out " + out.string());
        ASSERT_EQ(o.code, 0) << o.output;
        std::ifstream f(out / "results.json");
        const auto doc = nlohmann::json::parse(f);
        ASSERT_EQ(doc["runs"].size(), 1u);
        EXPECT_EQ(doc["runs"][0]["timing"]["views"], views);
        EXPECT_EQ(doc["runs"][0]["frame"]["samples_ms"].size(), 8u);
        const fs::path id = out / "corner/alchemy_fast/n16/b4/full/64x36/vk/compute";
        for (int i = 0; i < 2; ++i) {
            std::ifstream png(id / (i ? "color.png" : "ao_blur.png"), std::ios::binary);
            bytes[views == 4][i].assign(std::istreambuf_iterator<char>(png), {});
            EXPECT_FALSE(bytes[views == 4][i].empty());
        }
    }
    EXPECT_EQ(bytes[0][0], bytes[1][0]) << "ao_blur.png differs";
    EXPECT_EQ(bytes[0][1], bytes[1][1]) << "color.png differs";
    EXPECT_EQ(cavity("run --views 5 --list").code, 2);
}

// A kernel's own parameter swept over a mixed selection reaches only the
// kernels that read it: alchemy keeps one configuration with no slices
// segment, gtao gets one per value.
TEST_F(Cli, AParameterOfOneKernelStaysOutOfTheOthersIds) {
    const Outcome o = cavity("run --kernel alchemy,gtao --slices 1,3 --backend vk --list");
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_EQ(o.output, "corner/alchemy/n16/b4/full/320x180/vk/compute\n"
                        "corner/gtao/n16/b4/slices=1/full/320x180/vk/compute\n"
                        "corner/gtao/n16/b4/slices=3/full/320x180/vk/compute\n");
    // --blur 0 decides that no blur pass runs: it stays in the id.
    const Outcome b = cavity("run --kernel alchemy --blur 0 --backend vk --list");
    EXPECT_EQ(b.output, "corner/alchemy/n16/b0/full/320x180/vk/compute\n");
}

// cavity quality with the kernels' times: rows sorted by error, the
// screen-space Pareto front, and the best within a budget, each checked
// against the rows it came from.
TEST_F(Cli, QualityRecommendsTheBestScreenSpaceKernelWithinABudget) {
    fs::create_directories(dir);
    const std::map<std::string, double> ms = {{"alchemy/n8", 0.10}, {"alchemy/n16", 0.20}, {"hemisphere_fast/n8", 0.08},
                                              {"hemisphere_fast/n16", 0.15}, {"sdf_classic/n8", 0.01}, {"sdf_classic/n16", 0.02}};
    nlohmann::json bench = {{"context", {{"cavity_sweep", "gpu"}}}, {"benchmarks", nlohmann::json::array()}};
    for (const auto& [k, t] : ms)
        bench["benchmarks"].push_back({{"name", "corner/" + k + "/b4/full/64x36/vk/compute/iterations:1/manual_time"},
                                       {"run_type", "iteration"}, {"real_time", t}, {"time_unit", "ms"},
                                       {"label", "clock=gpu-timestamp mode=batch"}});
    const fs::path cost = dir / "bench.json";
    std::ofstream(cost) << bench.dump();
    const Outcome o = cavity("quality --kernel alchemy,hemisphere_fast,sdf_classic --samples 8,16 --res 64x36 --scene corner "
                             "--quiet --cost " + cost.string() + " --budget-ms 0.16 --out " + (dir / "q").string());
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(dir / "q" / "quality.json");
    const auto doc = nlohmann::json::parse(f);
    EXPECT_EQ(doc["reach"], "shared");   // the default now
    // The cost column names where its times come from.
    EXPECT_EQ(doc["cost_source"]["text"], "cost ms: the AO pipeline's median time (G-buffer left out) from " + cost.string() +
                                              ", over vk, compute at the largest of 64x36, on GPU timestamps");
    EXPECT_FALSE(doc["cost_source"]["software_renderer"].get<bool>());
    EXPECT_NE(o.output.find(doc["cost_source"]["text"].get<std::string>()), std::string::npos) << o.output;
    const auto& rec = doc["recommendation"];
    // The best within --budget-ms: the least error among screen-space kernels that fit.
    double best = 1e9;
    for (const auto& c : rec["candidates"])
        if (c["screen_space"].get<bool>() && c["cost_ms"].get<double>() <= 0.16) best = std::min(best, c["mae"].get<double>());
    ASSERT_FALSE(rec["best"].is_null()) << o.output;
    EXPECT_DOUBLE_EQ(rec["best"]["mae"].get<double>(), best);
    EXPECT_NE(rec["best"]["kernel"], "sdf_classic");
    // The front: cheapest first, each more accurate than the one before, and
    // no screen-space candidate better on both counts than one of it.
    double lastMae = 1e9, lastCost = -1;
    for (const auto& p : rec["pareto"]) {
        EXPECT_NE(p["kernel"], "sdf_classic");
        EXPECT_LT(p["mae"].get<double>(), lastMae);
        EXPECT_GE(p["cost_ms"].get<double>(), lastCost);
        lastMae = p["mae"];
        lastCost = p["cost_ms"];
        for (const auto& c : rec["candidates"]) {
            if (!c["screen_space"].get<bool>()) continue;
            EXPECT_FALSE(c["mae"].get<double>() < p["mae"].get<double>() &&
                         c["cost_ms"].get<double>() < p["cost_ms"].get<double>()) << c << " dominates " << p;
        }
    }
    // The table is sorted by error within the scene.
    double previous = -1;
    std::istringstream lines(o.output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("corner ", 0) == 0) {
            std::istringstream cells(line);
            std::string scene, kernel;
            int samples = 0;
            double mae = 0;
            cells >> scene >> kernel >> samples >> mae;
            EXPECT_GE(mae, previous) << line;
            previous = mae;
        }
    // Times from a software renderer: said beside the column and the pick.
    bench["context"]["cavity_software_renderer"] = "true";
    std::ofstream(cost) << bench.dump();
    const Outcome soft = cavity("quality --kernel alchemy,hemisphere_fast --samples 8 --res 64x36 --scene corner --quiet "
                                "--cost " + cost.string() + " --budget-ms 0.16");
    ASSERT_EQ(soft.code, 0) << soft.output;
    EXPECT_NE(soft.output.find("measured on a software renderer: the host CPU's time, not a GPU's"), std::string::npos)
        << soft.output;
    EXPECT_NE(soft.output.find("on a software renderer's times: say nothing of a GPU budget"), std::string::npos)
        << soft.output;
    // --budget-ms alone is refused.
    const Outcome lone = cavity("quality --budget-ms 0.1");
    EXPECT_EQ(lone.code, 2) << lone.output;
    EXPECT_NE(lone.output.find("--budget-ms: needs --cost"), std::string::npos) << lone.output;
}

// stdout only (stderr to /dev/null), and the exit code.
Outcome stdoutOf(const std::string& args) { return cavity(args, "", "2>/dev/null"); }
// stderr only.
Outcome stderrOf(const std::string& args) { return cavity(args, "", "2>&1 >/dev/null"); }

TEST_F(Cli, HelpOnEveryCommandPrintsToStdoutAndExitsZero) {
    for (const std::string c : {"--help", "run --help", "run -h", "gate --help", "gate judge --help", "gate merge --help",
                                "baselines update --help", "compare --help", "quality --help"}) {
        const Outcome o = stdoutOf(c);
        EXPECT_EQ(o.code, 0) << c << "\n" << o.output;
        EXPECT_NE(o.output.find("--"), std::string::npos) << c << "\n" << o.output;
    }
    // Help wins wherever it stands, even after a bad value.
    EXPECT_EQ(stdoutOf("run --samples 0 --help").code, 0);
    // `cavity` alone: the command list, exit 2 (README, Exit codes).
    const Outcome bare = stdoutOf("");
    EXPECT_EQ(bare.code, 2);
    EXPECT_NE(bare.output.find("quality"), std::string::npos) << bare.output;
}

// Text with every run of spaces and line breaks as one space: --help wraps
// its lines at 100 columns, so a summary may span two of them.
std::string oneLine(const std::string& text) { return std::regex_replace(text, std::regex(R"(\s+)"), " "); }

TEST_F(Cli, RunHelpNamesEveryKernelAndParameterWithDefaultAndRange) {
    const Outcome o = stdoutOf("run --help");
    ASSERT_EQ(o.code, 0);
    const std::string help = oneLine(o.output);
    for (const auto& k : cavity::kernels::all()) {
        if (k.role != cavity::kernels::Role::Ao && k.role != cavity::kernels::Role::Reference) continue;
        EXPECT_NE(help.find(k.name), std::string::npos) << k.name;
        const std::string summary = oneLine(k.summary);
        EXPECT_NE(help.find(summary), std::string::npos) << k.name << " summary";
        // The kernel's entry: its summary, then the published sources it follows.
        if (!k.sources.empty()) {
            std::string sources = " [after " + k.sources[0];
            for (size_t i = 1; i < k.sources.size(); ++i) sources += "; " + k.sources[i];
            EXPECT_NE(help.find(summary + sources + "]"), std::string::npos) << k.name << ": " << sources;
        }
        for (const auto& p : k.params) {
            EXPECT_NE(help.find("--" + p.name() + " "), std::string::npos) << "--" << p.name();
            EXPECT_NE(help.find(oneLine(p.decl->help)), std::string::npos) << "--" << p.name() << " help";
            if (!p.note.empty()) {
                EXPECT_NE(help.find(oneLine(p.note)), std::string::npos) << k.name << " --" << p.name();
            }
        }
    }
    EXPECT_NE(help.find("default 0.5, 0.13 (sdf_classic)"), std::string::npos);   // --radius: a kernel's own default
    EXPECT_NE(help.find("integer 1..256 samples"), std::string::npos);  // --samples
}

// Examples are one line each, never wrapped, so that each can be copied
// and pasted; the rest of the help wraps at 100 columns.
TEST_F(Cli, EveryHelpWrapsAt100ColumnsAndEndsWithUnwrappedExamples) {
    for (const std::string command :
         {"run", "gate", "gate judge", "gate merge", "baselines update", "baselines approve", "compare", "quality", "ab",
          "history ingest", "baselines migrate-digests"}) {
        const Outcome o = stdoutOf(command + " --help");
        ASSERT_EQ(o.code, 0) << command;
        std::istringstream lines(o.output);
        std::string line, last;
        bool inExamples = false;
        while (std::getline(lines, line)) {
            if (line == "Examples:") {
                inExamples = true;
            } else if (inExamples && !line.empty()) {
                EXPECT_EQ(line.rfind("  cavity ", 0), 0u) << command << ": an example wrapped: " << line;
            } else if (!inExamples) {
                EXPECT_LE(line.size(), 100u) << command << ": " << line;
            }
            // Their text holds a "..." of its own (a sequence, a set of values).
            const bool prose = command == "ab" || command == "history ingest";
            if (!prose) {
                EXPECT_EQ(line.find(" ..."), std::string::npos) << command << ": a parser leftover: " << line;
            }
            if (!line.empty()) last = line;
        }
        const size_t examples = o.output.rfind("\nExamples:\n");
        ASSERT_NE(examples, std::string::npos) << command;
        EXPECT_EQ(last.rfind("  cavity " + command, 0), 0u) << command << ": ends with " << last;
    }
}

TEST_F(Cli, UnknownFlagNamesItsNearestNeighbour) {
    const std::vector<BadCase> cases = {
        {"run --radiuss 1", "cavity run: --radiuss: unknown flag (did you mean --radius? see cavity run --help)"},
        {"run --samles 8", "cavity run: --samles: unknown flag (did you mean --samples?"},
        {"run --half", "cavity run: --half: unknown flag"},   // a switch that does not exist: not "missing value"
        {"gate --matrx ci", "cavity gate: --matrx: unknown flag (did you mean --matrix?"},
        {"gate merge --outt x", "cavity gate merge: --outt: unknown flag (did you mean --out?"},
        {"compare a.json b.json --alpah 0.1", "cavity compare: --alpah: unknown flag (did you mean --alpha?"},
        {"quality --sampls 8", "cavity quality: --sampls: unknown flag (did you mean --samples?"},
        {"baselines update --form x", "cavity baselines update: --form: unknown flag (did you mean --from?"},
        {"rnu", "cavity: unknown command 'rnu' (did you mean run?)"},
    };
    for (const auto& c : cases) {
        const Outcome o = cavity(c.args);
        EXPECT_EQ(o.code, 2) << c.args << "\n" << o.output;
        EXPECT_EQ(o.output.rfind(c.message, 0), 0u) << c.args << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << c.args << "\n" << o.output;
    }
}

TEST_F(Cli, ListPrintsExactlyWhatTheRunRuns) {
    const std::string sweep = "run --backend vk --samples 4,8 --radius 0.5,1 --res 32x18 --frames 1 --warmup 0 "
                              "--out " + dir.string();
    const Outcome list = stdoutOf(sweep + " --filter '/n(4|8)/' --list");
    ASSERT_EQ(list.code, 0) << list.output;
    EXPECT_FALSE(fs::exists(dir));
    std::vector<std::string> listed;
    std::istringstream lines(list.output);
    for (std::string l; std::getline(lines, l);) listed.push_back(l);
    ASSERT_EQ(listed.size(), 4u) << list.output;
    const Outcome run = cavity(sweep + " --filter '/n(4|8)/' --quiet");
    ASSERT_EQ(run.code, 0) << run.output;
    std::ifstream f(dir / "results.json");
    const auto doc = nlohmann::json::parse(f);
    std::vector<std::string> ran;
    for (const auto& r : doc["runs"]) ran.push_back(r["id"]);
    EXPECT_EQ(ran, listed);
    // --filter narrows it, with the id syntax of the gate.
    const Outcome one = stdoutOf(sweep + " --list --filter '^corner/alchemy/n8/b4/radius=1/'");
    EXPECT_EQ(one.output, "corner/alchemy/n8/b4/radius=1/full/32x18/vk/compute\n");
    EXPECT_EQ(cavity(sweep + " --list --filter nomatch").code, 2);
}

TEST_F(Cli, ProgressLinesAppearInAPipe) {
    const std::string sweep = "run --backend vk --samples 4,8 --res 32x18 --frames 1 --warmup 0 --out " + dir.string();
    const Outcome o = stderrOf(sweep);
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_NE(o.output.find("[1/2] corner/alchemy/n4/b4/full/32x18/vk/compute  elapsed "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("[2/2] corner/alchemy/n8/b4/full/32x18/vk/compute  elapsed "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("ETA"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find('\r'), std::string::npos) << "a pipe gets plain lines";
    fs::remove_all(dir);
    const Outcome quiet = stderrOf(sweep + " --quiet");
    EXPECT_EQ(quiet.output.find("[1/2]"), std::string::npos) << quiet.output;
}

}  // namespace
