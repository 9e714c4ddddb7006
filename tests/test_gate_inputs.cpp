// Bad gate inputs are reported as bad input (exit 2, one line naming the
// file), never silently passed; `baselines update` rewrites only what it is
// asked to, atomically.
#include "run_binary.h"
#include "images/image_io.h"
#include "plan/approvals.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <random>
#include <sstream>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace fs = std::filesystem;

namespace {

using ::cavity::test::Outcome;

Outcome run(const std::string& args, const std::string& env = "") {
    return ::cavity::test::runBinary(CAVITY_EXE, args, env);
}

std::string checksum(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    const std::string d((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    return std::to_string(std::hash<std::string>{}(d)) + ":" + std::to_string(d.size());
}

std::map<std::string, std::string> checksums(const fs::path& root) {
    std::map<std::string, std::string> m;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file()) m[fs::relative(e.path(), root).string()] = checksum(e.path());
    return m;
}

class GateInputs : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("cavity-gate-inputs-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        base = dir / "baselines";
        fs::copy(fs::path(CAVITY_SOURCE_DIR) / "baselines", base, fs::copy_options::recursive);
        fs::remove_all(base / "store");   // a checkout's own store (ignored by git) is not a clone's
        ::cavity::test::dropCpuApprovals(base.string());
    }
    void TearDown() override { fs::remove_all(dir); }
    Outcome gate(const std::string& extra = "") {
        return run("gate --matrix smoke --baselines " + base.string() + " --out " + (dir / "out").string() + " " + extra);
    }
    fs::path image(const std::string& name) { return base / "images/corner/alchemy/n16/b4/full/160x90" / name; }
    void expectBad(const Outcome& o, const std::string& mustName) {
        EXPECT_EQ(o.code, 2) << o.output;
        const std::string first = o.output.substr(0, o.output.find('\n'));
        EXPECT_NE(first.find(mustName), std::string::npos) << o.output;
        EXPECT_EQ(first.rfind("cavity gate: ", 0), 0u) << o.output;
    }
    fs::path dir, base;
};

TEST_F(GateInputs, MissingBaselineIsBadInputNamingTheFile) {
    fs::remove(image("ao.exr"));
    const Outcome o = gate();
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find("baseline missing: " + image("ao.exr").string()), std::string::npos) << o.output;
}

TEST_F(GateInputs, CorruptBaselineIsBadInput) {
    std::ofstream(image("ao.exr"), std::ios::trunc) << "not an exr";
    expectBad(gate(), image("ao.exr").string());
}

TEST_F(GateInputs, BaselineOfTheWrongSizeIsBadInput) {
    ASSERT_TRUE(cavity::images::writeImage(image("ao.exr").string(), cavity::core::HostImage(80, 45, 1, 1.0f)).ok());
    expectBad(gate(), image("ao.exr").string() + ": baseline is 80x45x1, configuration needs 160x90x1");
}

TEST_F(GateInputs, BaselineWithTheWrongChannelCountIsBadInput) {
    ASSERT_TRUE(cavity::images::writeImage(image("ao.exr").string(), cavity::core::HostImage(160, 90, 3, 1.0f)).ok());
    expectBad(gate(), image("ao.exr").string() + ": baseline is 160x90x3, configuration needs 160x90x1");
}

TEST_F(GateInputs, ManifestWithAnUnknownKeyIsBadInput) {
    std::ofstream(base / "manifest.json", std::ios::trunc)
        << R"({"pipelines": {"*": {"max_abss": 0.1}}})";
    expectBad(gate(), "manifest.json: unknown key 'max_abss'");
}

TEST_F(GateInputs, ManifestWithAnUnknownDeviceScopeIsBadInput) {
    std::ofstream(base / "manifest.json", std::ios::trunc)
        << R"({"devices": [{"pattern": "llvmpipe", "scope": "sometimes", "pipelines": {"*": {"rmse": 0.001}}}]})";
    expectBad(gate(), "devices[0].scope is \"sometimes\": must be \"baselines\" (against the stored baselines only) or \"all\"");
}

TEST_F(GateInputs, ManifestWithAFractionalSizeIsBadInput) {
    std::ofstream(base / "manifest.json", std::ios::trunc)
        << R"({"pipelines": {"*": {"mean_abs": 0.001, "sized_for_pixels": 1.5}}})";
    expectBad(gate(), "pipelines.*.sized_for_pixels is 1.5: must be a whole number of pixels (0: any size)");
}

TEST_F(GateInputs, ManifestWithANegativeToleranceIsBadInput) {
    std::ofstream(base / "manifest.json", std::ios::trunc) << R"({"pipelines": {"alchemy": {"rmse": -0.5}}})";
    expectBad(gate(), "pipelines.alchemy.rmse is -0.5: tolerances must be >= 0");
}

TEST_F(GateInputs, BudgetsThatDoNotParseAreBadInput) {
    std::ofstream(base / "budgets.json", std::ios::trunc) << "{ \"devices\": [ ";
    expectBad(gate(), "budgets.json: does not parse");
}

// The CI machine renders on llvmpipe and lavapipe: a budget overrun there is
// the host's load as often as the kernel's, so it is reported, not failed,
// unless --enforce-cpu-budgets.
TEST_F(GateInputs, CpuBudgetOverrunIsReportedAndFailsOnlyWhenEnforced) {
    std::ofstream(base / "budgets.json", std::ios::trunc)
        << R"({"devices": [{"pattern": "", "budgets_ms": {"corner/alchemy/n16/b4/full/160x90/vk/compute": {"ao": 1e-9}}}]})";
    const Outcome advisory = gate();
    EXPECT_EQ(advisory.code, 0) << advisory.output;
    EXPECT_NE(advisory.output.find("1 pass timings over budget on a software renderer (reported, not failed"),
              std::string::npos) << advisory.output;
    const Outcome enforced = gate("--enforce-cpu-budgets");
    EXPECT_EQ(enforced.code, 1) << enforced.output;
    EXPECT_NE(enforced.output.find("time ao"), std::string::npos) << enforced.output;
    EXPECT_NE(enforced.output.find("ms (+"), std::string::npos) << enforced.output;
    // Budgets are not images: the update says what to run instead.
    const Outcome update = run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string());
    EXPECT_EQ(update.code, 0) << update.output;
    EXPECT_NE(update.output.find("0 baseline files updated"), std::string::npos) << update.output;
    EXPECT_NE(update.output.find("1 configurations failed on time budgets only (every image passed)"), std::string::npos)
        << update.output;
    EXPECT_NE(update.output.find("scripts/update_budgets.py " + (dir / "out" / "gate.json").string()), std::string::npos)
        << update.output;
    // ... a command that runs as printed, from the source tree: it updates the
    // entry the gate read, in these baselines, and the enforced gate passes.
    const size_t from = update.output.find("`python3 ") + 1, to = update.output.find('`', from);
    ASSERT_NE(to, std::string::npos) << update.output;
    const std::string command = update.output.substr(from, to - from);
    EXPECT_NE(command.find("--budgets " + (base / "budgets.json").string()), std::string::npos) << command;
    ASSERT_EQ(std::system(("cd " + std::string(CAVITY_SOURCE_DIR) + " && " + command + " >/dev/null").c_str()), 0) << command;
    EXPECT_EQ(gate("--enforce-cpu-budgets").code, 0);
}

TEST_F(GateInputs, ExpectationsFolderThatIsNotOneIsBadInput) {
    expectBad(gate("--expectations " + (dir / "nowhere").string()), "--expectations " + (dir / "nowhere").string() + ": no such folder");
    std::ofstream(dir / "file.txt") << "device .\n";
    expectBad(gate("--expectations " + (dir / "file.txt").string()), ": not a folder");
}

// A shader edit gated in one step: `cavity gate --kernel-source`, with the
// file and its digest in every report.
TEST_F(GateInputs, KernelSourceEditFailsTheGateAndEveryReportNamesIt) {
    std::ifstream in(fs::path(CAVITY_SOURCE_DIR) / "kernels/ao/alchemy/ssao_alchemy.glsl");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const std::string find = "- P.bias";
    ASSERT_NE(text.find(find), std::string::npos);
    text.replace(text.find(find), find.size(), "+ P.bias");
    const fs::path edit = dir / "bias_flipped.glsl";
    std::ofstream(edit) << text;
    const Outcome o = gate("--retries 0 --kernel-source ssao_alchemy.glsl=" + edit.string());
    EXPECT_EQ(o.code, 1) << o.output;
    const fs::path out = dir / "out";
    std::ifstream gj(out / "gate.json");
    const auto j = nlohmann::json::parse(gj);
    ASSERT_EQ(j["kernel_sources"].size(), 1u) << j["kernel_sources"];
    EXPECT_EQ(j["kernel_sources"][0]["name"], "ao/alchemy/ssao_alchemy.glsl");
    EXPECT_EQ(j["kernel_sources"][0]["file"], edit.string());
    const std::string digest = j["kernel_sources"][0]["digest"];
    EXPECT_EQ(digest.rfind("fnv1a64:", 0), 0u) << digest;
    for (const char* report : {"summary.md", "junit.xml", "index.html"}) {
        std::ifstream f(out / report);
        const std::string t((std::istreambuf_iterator<char>(f)), {});
        EXPECT_NE(t.find(edit.string()), std::string::npos) << report;
        EXPECT_NE(t.find(digest), std::string::npos) << report;
    }
}

TEST_F(GateInputs, KernelSourceThatCannotApplyIsBadInput) {
    const fs::path glsl = dir / "edit.glsl", binary = dir / "edit.bin";
    std::ofstream(glsl) << "void cavity_main(ivec2 pixel) {}\n";
    std::ofstream(binary, std::ios::binary) << std::string("\x7f" "ELF\0\0\x01", 7);
    expectBad(gate("--kernel-source ssao_alchemy.glsl=" + binary.string()), "not a text file (a NUL byte at offset 4");
    expectBad(gate("--kernel-source ssao_alchemy.glsl=" + dir.string()), ": not a file");
    expectBad(gate("--kernel-source ssao_alchemy.glsl=" + (dir / "none.glsl").string()), ": no such file");
    expectBad(gate("--kernel-source nope.glsl=" + glsl.string()), "--kernel-source nope.glsl: no kernel source of that name");
    expectBad(gate("--kernel-source ssao_alchemy.glsl=" + glsl.string() + " --kernel-source ssao_alchemy.glsl=" + glsl.string()),
              "is already replaced (give each NAME once)");
    // The smoke matrix runs alchemy: SSDO's direct pass is never compiled.
    expectBad(gate("--kernel-source ssdo_direct.glsl=" + glsl.string()), "no configuration of the selection compiles kernels/ao/ssdo/ssdo_direct.glsl");
}

// A compile error in a replacement names the file given, not kernels/NAME.
TEST_F(GateInputs, KernelSourceCompileErrorNamesTheFileGiven) {
    const fs::path broken = dir / "broken.glsl";
    std::ofstream(broken) << "void cavity_main(ivec2 pixel) { this is not glsl; }\n";
    const Outcome o = gate("--retries 0 --kernel-source ssao_alchemy.glsl=" + broken.string());
    EXPECT_NE(o.code, 0) << o.output;
    EXPECT_NE(o.output.find(broken.string() + " (replacing kernels/ao/alchemy/ssao_alchemy.glsl):1"), std::string::npos) << o.output;
}

// Approvals (baselines/approvals.json): an approved digest of the device's
// class passes with no metric computed; a known-bad digest fails on any
// device; an approval of another class changes nothing (tolerance route).
TEST_F(GateInputs, ApprovedDigestsPassAtOnceAndKnownBadOnesFail) {
    const fs::path out = dir / "out";
    ASSERT_EQ(gate().code, 0);
    const Outcome noWhy = run("baselines approve --from " + out.string() + " --baselines " + base.string());
    EXPECT_EQ(noWhy.code, 2) << noWhy.output;
    EXPECT_NE(noWhy.output.find("--why: required"), std::string::npos) << noWhy.output;
    // Refusals write nothing: neither approvals.json nor the store.
    const std::string before = checksum(base / "approvals.json");
    const auto storeFiles = [&] {
        size_t n = 0;
        std::error_code ec;
        for (fs::recursive_directory_iterator it(base / "store", ec), end; !ec && it != end; it.increment(ec)) n += it->is_regular_file();
        return n;
    };
    const size_t stored = storeFiles();
    const std::string approve0 = "baselines approve --from " + out.string() + " --baselines " + base.string() + " ";
    for (const auto& [args, needle] : std::vector<std::pair<std::string, std::string>>{
             {"--why '   '", "--why '   ': blanks only"},
             {"--why x --filter '^nosuch/'", "--filter ^nosuch/: matches no configuration"}}) {
        const Outcome o = run(approve0 + args);
        EXPECT_EQ(o.code, 2) << args << "\n" << o.output;
        EXPECT_NE(o.output.find(needle), std::string::npos) << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
        EXPECT_EQ(checksum(base / "approvals.json"), before) << args;
        EXPECT_EQ(storeFiles(), stored) << args;
    }
    // What a kill -9 left (a process id that no longer runs) goes with the next write.
    fs::create_directories(base / "store" / "sha256");
    const fs::path staleJson = base / "approvals.json.tmp-999999999",
                   staleObject = base / "store/sha256" / (std::string(64, 'a') + ".f32z.tmp-999999999");
    std::ofstream(staleJson) << "{";
    std::ofstream(staleObject) << "half";
    const Outcome approve = run("baselines approve --from " + out.string() + " --baselines " + base.string() +
                                " --by tester --why 'the CPU references'");
    ASSERT_EQ(approve.code, 0) << approve.output;
    EXPECT_FALSE(fs::exists(staleJson));
    EXPECT_FALSE(fs::exists(staleObject));
    EXPECT_NE(approve.output.find("6 image digests approved"), std::string::npos) << approve.output;
    auto routes = [&] {
        std::ifstream f(out / "gate.json");
        const auto j = nlohmann::json::parse(f);
        std::map<std::string, int> n;
        for (const auto& r : j["results"])
            for (const auto& i : r["images"]) {
                ++n[i["route"].get<std::string>()];
                if (i["route"] == "digest") {
                    EXPECT_TRUE(i["metrics"].is_null()) << i;
                }
            }
        return n;
    };
    const Outcome byDigest = gate();
    EXPECT_EQ(byDigest.code, 0) << byDigest.output;
    EXPECT_EQ(routes(), (std::map<std::string, int>{{"digest", 6}}));
    EXPECT_NE(byDigest.output.find("images decided: 6 by approved digest"), std::string::npos) << byDigest.output;
    // The same digests approved for another class only: judged by tolerance.
    std::ifstream in(base / "approvals.json");
    auto doc = nlohmann::json::parse(in);
    in.close();
    for (auto& a : doc["approvals"]) a["device_class"] = "nvidia-h200";
    std::ofstream(base / "approvals.json", std::ios::trunc) << doc.dump(2);
    ASSERT_EQ(gate().code, 0);
    EXPECT_EQ(routes(), (std::map<std::string, int>{{"tolerance", 6}}));
    // Known bad, on whatever device: fails at once, naming who said so.
    const Outcome negative = run("baselines approve --from " + out.string() + " --baselines " + base.string() +
                                 " --negative --by tester --filter '/vk/' --why 'planted for the test'");
    ASSERT_EQ(negative.code, 0) << negative.output;
    const Outcome bad = gate();
    EXPECT_EQ(bad.code, 1) << bad.output;
    EXPECT_EQ(routes(), (std::map<std::string, int>{{"negative", 3}, {"tolerance", 3}}));
    EXPECT_NE(bad.output.find("known bad"), std::string::npos) << bad.output;
}

// The tolerance route's reference: the nearest approved image of the
// device's own class, fetched from the store with the default tolerances,
// else (no positive of the class) the default class's stored baseline with
// the manifest's device overrides. A store that lacks the reference, or
// holds another image under its digest, stops the judge with its own code.
TEST_F(GateInputs, ToleranceJudgesAgainstTheClassReferenceElseTheDefault) {
    const fs::path out = dir / "out", st = dir / "store";
    ASSERT_EQ(gate().code, 0);
    const Outcome approve = run("baselines approve --from " + out.string() + " --baselines " + base.string() + " --store " +
                                st.string() + " --by tester --why 'llvmpipe references'");
    ASSERT_EQ(approve.code, 0) << approve.output;
    size_t objects = 0;
    for (const auto& e : fs::recursive_directory_iterator(st)) objects += e.is_regular_file();
    EXPECT_GE(objects, 3u) << approve.output;   // gl and vk may share an image
    std::ifstream in(fs::path(CAVITY_SOURCE_DIR) / "kernels/ao/alchemy/ssao_alchemy.glsl");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text.replace(text.find("- P.bias"), 8, "- 0.9 * P.bias");
    const fs::path edit = dir / "bias_scaled.glsl";
    std::ofstream(edit) << text;
    const std::string planted = "--retries 0 --store " + st.string() + " --kernel-source ssao_alchemy.glsl=" + edit.string();
    auto images = [&] {
        std::ifstream f(out / "gate.json");
        std::vector<nlohmann::json> v;
        const auto doc = nlohmann::json::parse(f);
        for (const auto& r : doc["results"])
            for (const auto& i : r["images"]) v.push_back(i);
        return v;
    };
    const Outcome own = gate(planted);
    EXPECT_EQ(own.code, 1) << own.output;
    ASSERT_EQ(images().size(), 6u);
    int failed = 0;
    for (const auto& i : images()) {
        EXPECT_EQ(i["route"], "tolerance") << i;
        const std::string ref = i["reference"];
        EXPECT_TRUE(ref == "llvmpipe gl/compute" || ref == "llvmpipe vk/compute") << ref;
        EXPECT_EQ(i["baseline"].get<std::string>().rfind("store:sha256:", 0), 0u) << i;
        EXPECT_NE(i["approval"].get<std::string>().find("llvmpipe references"), std::string::npos) << i;
        failed += !i["passed"].get<bool>();
    }
    EXPECT_GT(failed, 0);
    // Approved for another class only: the default reference, by file.
    std::ifstream ain(base / "approvals.json");
    auto doc = nlohmann::json::parse(ain);
    ain.close();
    for (auto& a : doc["approvals"])
        if (a["by"] == "tester") a["device_class"] = "some-other-gpu";
    std::ofstream(base / "approvals.json", std::ios::trunc) << doc.dump(2);
    EXPECT_EQ(gate(planted).code, 1);
    for (const auto& i : images()) {
        EXPECT_EQ(i["reference"], "default") << i;
        EXPECT_NE(i["baseline"].get<std::string>().find("baselines/images/corner/alchemy"), std::string::npos) << i;
    }
    for (auto& a : doc["approvals"])
        if (a["by"] == "tester") a["device_class"] = "llvmpipe";
    std::ofstream(base / "approvals.json", std::ios::trunc) << doc.dump(2);
    // Another image filed under the reference's digest: exit 6, one line on
    // stderr, and a whole report whose configurations say so.
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(st))
        if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::vector<std::string> kept;
    for (const auto& f : files) kept.push_back(checksum(f));
    for (const auto& f : files) fs::copy_file(files[0] == f ? files[1] : files[0], f, fs::copy_options::overwrite_existing);
    const Outcome corrupt = ::cavity::test::runBinary(CAVITY_EXE, "gate --matrix smoke --baselines " + base.string() +
                                                      " --out " + (dir / "out").string() + " " + planted, "", "2>&1 >/dev/null");
    EXPECT_EQ(corrupt.code, 6) << corrupt.output;
    EXPECT_NE(corrupt.output.find("corrupt: its pixels have digest"), std::string::npos) << corrupt.output;
    EXPECT_EQ(std::count(corrupt.output.begin(), corrupt.output.end(), '\n'), 1) << corrupt.output;
    {
        std::ifstream f(dir / "out" / "gate.json");
        const auto g = nlohmann::json::parse(f);
        ASSERT_FALSE(g["results"].empty());
        for (const auto& r : g["results"]) {
            EXPECT_EQ(r["verdict"], "error") << r;
            EXPECT_NE(r["error"].get<std::string>().find("corrupt"), std::string::npos) << r;
        }
    }
    // A store without the reference: exit 5, one line naming the digest.
    // A store without the reference. A software renderer's approvals are
    // digests (a clone has no store): the stored baseline judges instead,
    // and the planted defect still fails. (A GPU class's missing reference
    // stays exit 5, naming the digest.)
    fs::remove_all(st);
    const Outcome missing = gate(planted);
    EXPECT_EQ(missing.code, 1) << missing.output;
    for (const auto& i : images()) {
        EXPECT_EQ(i["reference"], "default") << i;
        EXPECT_NE(i["baseline"].get<std::string>().find("baselines/images/corner/alchemy"), std::string::npos) << i;
    }
}

TEST(Approvals, TheNearestReferenceOfTheClassIsTheSameApiAndStageElseTheLatest) {
    cavity::plan::Approvals a;
    auto add = [&](std::string digest, std::string cls, std::string api, std::string stage, std::string when, bool pos = true) {
        a.entries.push_back({"k", "ao", digest, pos, cls, api, stage, "", "t", when, "w"});
    };
    add("fnv1a64:0000000000000001", "gpu-a", "gl", "compute", "2026-01-01");
    add("fnv1a64:0000000000000002", "gpu-a", "vk", "fragment", "2026-01-02");
    add("fnv1a64:0000000000000003", "gpu-a", "vk", "compute", "2026-01-01");
    add("fnv1a64:0000000000000004", "gpu-a", "vk", "compute", "2026-01-03");
    add("fnv1a64:0000000000000005", "gpu-a", "vk", "compute", "2026-01-09", false);
    add("fnv1a64:0000000000000006", "gpu-b", "gl", "fragment", "2026-01-01");
    auto ref = [&](std::string cls, std::string api, std::string stage) {
        const auto* r = a.reference("k", "ao", cls, api, stage);
        return r ? r->digest.back() - '0' : 0;
    };
    EXPECT_EQ(ref("gpu-a", "vk", "compute"), 4);    // same API and stage, the latest; never a negative
    EXPECT_EQ(ref("gpu-a", "gl", "compute"), 1);
    EXPECT_EQ(ref("gpu-a", "gl", "fragment"), 1);   // the same API before the same stage
    EXPECT_EQ(ref("gpu-a", "vk", "fragment"), 2);
    EXPECT_EQ(ref("gpu-b", "vk", "compute"), 6);    // any of the class before another class
    EXPECT_EQ(ref("gpu-c", "gl", "compute"), 0);    // none: the default class's baseline
    EXPECT_EQ(a.reference("k", "color", "gpu-a", "gl", "compute"), nullptr);
}

TEST_F(GateInputs, ApprovalsThatDoNotParseAreBadInput) {
    std::ofstream(base / "approvals.json") << R"({"schema": "cavity.approvals/1", "approvals": [{"key": "k"}]})";
    expectBad(gate(), "approvals.json");
    std::ofstream(base / "approvals.json", std::ios::trunc) << R"({"schema": "cavity.approvals/2", "approvals": []})";
    expectBad(gate(), "schema");
}

TEST_F(GateInputs, UnknownMatrixIsBadInput) {
    const Outcome o = run("gate --matrix nope --baselines " + base.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.output.find("--matrix nope: no such matrix"), std::string::npos) << o.output;
}

TEST_F(GateInputs, UpdateRewritesOnlyTheSelectedEntries) {
    // Break one baseline so the gate fails exactly that configuration.
    const fs::path victim = image("ao_blur.exr");
    fs::copy_file(base / "images/slats/alchemy/n16/b4/full/160x90/ao_blur.exr", victim,
                  fs::copy_options::overwrite_existing);
    ASSERT_EQ(gate().code, 1);
    const auto before = checksums(base);
    // A filter that matches nothing updates nothing, and says so (exit 2).
    const Outcome none = run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string() +
                             " --filter no_such_configuration");
    EXPECT_EQ(none.code, 2) << none.output;
    EXPECT_NE(none.output.find("--filter no_such_configuration: matches no configuration"), std::string::npos) << none.output;
    EXPECT_EQ(checksums(base), before);
    // A gate folder moved after the gate (an artifact downloaded from CI)
    // is read from where it is now.
    fs::rename(dir / "out", dir / "moved");
    const Outcome u = run("baselines update --from " + (dir / "moved").string() + " --baselines " + base.string());
    ASSERT_EQ(u.code, 0) << u.output;
    EXPECT_NE(u.output.find("updated " + victim.string()), std::string::npos) << u.output;
    const auto after = checksums(base);
    std::vector<std::string> changed;
    for (const auto& [f, sum] : after)
        if (before.at(f) != sum) changed.push_back(f);
    // The failing image of the failing configuration, and nothing else.
    ASSERT_EQ(changed.size(), 1u) << u.output;
    EXPECT_EQ(changed[0], "images/corner/alchemy/n16/b4/full/160x90/ao_blur.exr");
    EXPECT_EQ(gate().code, 0);
    // No temporary file is left behind.
    for (const auto& e : fs::recursive_directory_iterator(base))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

// A run with a kernel source replaced: its images are not what kernels/
// renders. The update refuses them alone; with --with-kernel-source it takes
// the edit into kernels/ too, so tree and baselines agree. status.json says
// the run was not of the tree.
TEST_F(GateInputs, UpdateFromAnEditedKernelTakesTheEditOrNothing) {
    const fs::path stock = fs::path(CAVITY_SOURCE_DIR) / "kernels/ao/alchemy/ssao_alchemy.glsl";
    std::ifstream in(stock);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const std::string from = "dot(N, omega) - P.bias";
    ASSERT_NE(text.find(from), std::string::npos);
    const std::string edited = text.substr(0, text.find(from)) + "dot(N, omega) - 0.9 * P.bias" + text.substr(text.find(from) + from.size());
    const fs::path edit = dir / "edit.glsl";
    std::ofstream(edit) << edited;
    const Outcome g = gate("--kernel-source ssao_alchemy.glsl=" + edit.string());
    ASSERT_EQ(g.code, 1) << g.output;
    {
        std::ifstream f(dir / "out" / "status.json");
        const auto status = nlohmann::json::parse(f);
        EXPECT_NE(status["description"].get<std::string>().find("kernel source replaced (ao/alchemy/ssao_alchemy.glsl)"),
                  std::string::npos) << status.dump();
    }
    const auto before = checksums(base);
    const std::string update = "baselines update --from " + (dir / "out").string() + " --baselines " + base.string();
    const Outcome refused = run(update);
    EXPECT_EQ(refused.code, 2) << refused.output;
    EXPECT_NE(refused.output.find("--with-kernel-source"), std::string::npos) << refused.output;
    EXPECT_EQ(checksums(base), before);
    // The tree beside these baselines: its kernels/ takes the edit.
    const fs::path tree = dir / "kernels/ao/alchemy/ssao_alchemy.glsl";
    fs::create_directories(tree.parent_path());
    fs::copy_file(stock, tree);
    const Outcome took = run(update + " --with-kernel-source");
    ASSERT_EQ(took.code, 0) << took.output;
    EXPECT_NE(checksums(base), before);
    std::ifstream now(tree);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(now)), {}), edited);
    EXPECT_NE(took.output.find("copied " + edit.string() + " over " + tree.string()), std::string::npos) << took.output;
}

TEST_F(GateInputs, InterruptedUpdateLeavesTheOldFileWhole) {
    const fs::path victim = image("ao_blur.exr");
    fs::copy_file(base / "images/slats/alchemy/n16/b4/full/160x90/ao_blur.exr", victim,
                  fs::copy_options::overwrite_existing);
    ASSERT_EQ(gate().code, 1);
    const std::string old = checksum(victim);
    // The test hook stops the update after the copy and before the rename,
    // as a kill would.
    const Outcome u = run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string(),
                          "CAVITY_TEST_INTERRUPT_UPDATE=1");
    EXPECT_NE(u.code, 0);
    EXPECT_EQ(checksum(victim), old);
    // The next update cleans the leftover and completes.
    ASSERT_EQ(run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string()).code, 0);
    for (const auto& e : fs::recursive_directory_iterator(base)) {
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
        EXPECT_EQ(e.path().filename().string().find(".update-"), std::string::npos) << e.path();
    }
}

// A gate output that names a file that is gone: exit 2 before any baseline changes.
TEST_F(GateInputs, UpdateFromAnIncompleteOutputChangesNothing) {
    ASSERT_EQ(gate().code, 0);
    const auto before = checksums(base);
    std::vector<fs::path> victims;   // every API's, whichever the update would take
    for (const auto& e : fs::recursive_directory_iterator(dir / "out"))
        if (e.path().filename() == "ao_blur.new.exr") victims.push_back(e.path());
    ASSERT_FALSE(victims.empty()) << "the gate wrote no ao_blur.new.exr";
    for (const auto& v : victims) fs::remove(v);
    const Outcome u = run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string() +
                          " --filter .");
    EXPECT_EQ(u.code, 2) << u.output;
    EXPECT_NE(u.output.find("ao_blur.new.exr: missing or not a readable file"), std::string::npos) << u.output;
    EXPECT_EQ(checksums(base), before);
}

// SIGKILL at random instants of `baselines update`: after the next command,
// the images are the whole old set or the whole new set, and nothing is left over.
TEST_F(GateInputs, KilledUpdatesLeaveTheOldSetOrTheNewSet) {
    ASSERT_EQ(gate().code, 0);
    const std::string update = std::string(CAVITY_EXE) + " baselines update --from " + (dir / "out").string() +
                               " --baselines " + base.string() + " --filter . > /dev/null 2>&1";
    // Old set: the baselines with a byte appended, so that every file the update rewrites changes.
    const fs::path images = base / "images", saved = dir / "old-images";
    const auto t0 = std::chrono::steady_clock::now();
    const Outcome first = run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string() +
                              " --filter .");
    const double fullMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(first.code, 0) << first.output;
    const auto newSet = checksums(images);
    std::vector<fs::path> rewritten;   // from its "updated <path>  (from ...)" lines
    std::istringstream lines(first.output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("updated ", 0) == 0) rewritten.push_back(line.substr(8, line.find("  (from") - 8));
    ASSERT_GE(rewritten.size(), 3u) << first.output;
    for (const auto& f : rewritten) std::ofstream(f, std::ios::app | std::ios::binary) << '#';
    const auto oldSet = checksums(images);
    ASSERT_NE(oldSet, newSet);
    fs::copy(images, saved, fs::copy_options::recursive);
    std::mt19937 rng(20261201);
    std::uniform_real_distribution<double> at(0.0, 1.2 * fullMs);
    // 30 kills spread over the update's whole run: each is a full update
    // and a recovery, the longest part of this binary under a sanitizer.
    constexpr int kTrials = 30;
    int sawOld = 0, sawNew = 0;
    for (int trial = 0; trial < kTrials; ++trial) {
        fs::remove_all(images);
        fs::copy(saved, images, fs::copy_options::recursive);
        const pid_t pid = fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            execl("/bin/sh", "sh", "-c", ("exec " + update).c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(at(rng)));
        kill(pid, SIGKILL);
        int status = 0;
        waitpid(pid, &status, 0);
        // The next command that reads the baselines finishes or drops what
        // the kill interrupted (this one, whose filter matches nothing,
        // then refuses: exit 2, nothing more written).
        ASSERT_EQ(run("baselines update --from " + (dir / "out").string() + " --baselines " + base.string() +
                      " --filter no-configuration-matches-this").code, 2);
        const auto now = checksums(images);
        const bool isOld = now == oldSet, isNew = now == newSet;
        EXPECT_TRUE(isOld || isNew) << "trial " << trial << ": a mix of old and new baselines";
        sawOld += isOld;
        sawNew += isNew;
        for (const auto& e : fs::recursive_directory_iterator(base)) {
            const std::string name = e.path().filename().string();
            EXPECT_TRUE(name.find(".update-") == std::string::npos && name.find(".tmp-") == std::string::npos)
                << "trial " << trial << ": leftover " << e.path();
        }
    }
    EXPECT_EQ(sawOld + sawNew, kTrials);
    std::printf("%d kills within %.0f ms: %d left the old set, %d the new set\n", kTrials, 1.2 * fullMs, sawOld, sawNew);
}

}  // namespace
