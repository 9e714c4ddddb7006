// The cavity command as a user meets it: exit codes, one-line errors that
// name the flag, the value and what is allowed, and nothing written on bad input.
#include "kernel.h"
#include "sweep.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Outcome {
    int code = -1;
    std::string output;   // stdout and stderr
};

Outcome cavity(const std::string& args, const std::string& env = "") {
    const std::string cmd = env + " " + CAVITY_EXE + " " + args + " 2>&1";
    Outcome o;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return o;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) o.output.append(buf.data(), n);
    const int status = pclose(p);
    o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return o;
}

// The kernels --kernel accepts as the registry lists them, the way the
// message names them: the AO kernels, then the ground truth (role
// "reference", declared last).
std::string aoList() {
    std::string s;
    for (const auto& k : cavity::aoKernels()) s += (s.empty() ? "" : ", ") + k;
    for (const auto& k : cavity::kernels::all())
        if (k.role == "reference") s += ", " + k.name;
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

TEST_F(Cli, BadInputExitsTwoWithOneLineAndWritesNothing) {
    const std::vector<BadCase> cases = {
        {"--backend metal", "cavity run: --backend metal: must be gl, vk or all"},
        {"--scene moon", "cavity run: --scene moon: must be one of corner, slats, open, contact, grille, plates"},
        {"--view 4", "cavity run: --view 4: must be an integer in 0..3"},
        {"--kernel sdf_classic --strength -1", "cavity run: --strength -1: must be a number in 0..100"},
        {"--kernel ground_truth --rays 512", "cavity run: --rays 512: must be an integer in 1024..65536"},
        {"--kernel ground_truth --rays many", "cavity run: --rays 'many': must be an integer in 1024..65536"},
        {"--kernel nope", "cavity run: --kernel nope: unknown kernel (have: " + aoList() + ")"},
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
    };
    for (const auto& c : cases) {
        const Outcome o = cavity("quality " + c.args + " --out " + dir.string());
        EXPECT_EQ(o.code, 2) << c.args << "\n" << o.output;
        EXPECT_EQ(o.output.rfind(c.message, 0), 0u) << c.args << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << c.args << "\n" << o.output;
        EXPECT_FALSE(fs::exists(dir)) << c.args;
    }
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
    EXPECT_NE(o.output.find("median ms"), std::string::npos);
}

}  // namespace
