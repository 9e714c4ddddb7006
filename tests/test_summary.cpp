// summary.md stays short whatever fails (report/summary.cpp): at most
// kSummaryLines lines, failures grouped by kernel and check, worst first,
// OpenGL and Vulkan counted once when both fail the same way.
#include "harness_names.h"
#include "report/gate_report.h"
#include "report/verdict_text.h"

#include <gtest/gtest.h>

#include <sstream>

namespace cavity::test {
namespace {

using namespace cavity::harness;

ConfigResult failingResult(const std::string& kernel, int variant, const std::string& api, double rmse) {
    ConfigResult r;
    r.config.kernel = kernel;
    r.id = "corner/" + kernel + "/n" + std::to_string(variant) + "/b4/full/160x90/" + api + "/compute";
    r.key = "corner/" + kernel + "/n" + std::to_string(variant) + "/b4/full/160x90";
    ImageCheck i;
    i.image = "ao";
    i.failures = {"RMSE " + std::to_string(rmse) + " > 0.005", "max abs error 0.5 > 0.1 at (3,4)"};
    r.images.push_back(i);
    return r;
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);) ++n;
    return n;
}

// A shard of a split larger than the matrix holds no configuration: it
// says it judged nothing, never "all 0 configurations passed".
TEST(Summary, AnEmptyShardSaysItJudgedNothing) {
    GateRun run;
    run.matrix = "ci";
    run.shardIndex = 500;
    run.shardCount = 1000;
    const std::string s = report::summaryMarkdown(run);
    EXPECT_NE(s.find("nothing was judged"), std::string::npos) << s;
    EXPECT_EQ(s.find("passed"), std::string::npos) << s;
    EXPECT_NE(report::commitStatus(run, "")["description"].get<std::string>().find("nothing judged"), std::string::npos);
}

TEST(Summary, AtMostThirtyLinesForAnyNumberOfFailures) {
    for (int kernels : {1, 3, 20, 200}) {
        GateRun run;
        run.matrix = "ci";
        for (int k = 0; k < kernels; ++k)
            for (int v = 0; v < 5; ++v)
                for (const char* api : {"gl", "vk"})
                    run.results.push_back(failingResult("kernel" + std::to_string(k), v, api, 0.01 * (k + 1)));
        run.backendErrors = {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j"};
        const std::string s = report::summaryMarkdown(run);
        EXPECT_LE(lineCount(s), report::kSummaryLines) << kernels << " kernels:\n" << s;
        EXPECT_NE(s.find("](index.html)"), std::string::npos) << s;
    }
}

TEST(Summary, GroupsByKernelAndCheckWorstFirstWithTheApisMerged) {
    GateRun run;
    run.matrix = "ci";
    for (const char* api : {"gl", "vk"}) {
        run.results.push_back(failingResult("alchemy", 16, api, 0.006));
        run.results.push_back(failingResult("hemisphere", 16, api, 0.05));
    }
    run.results.push_back(failingResult("alchemy", 32, "vk", 0.007));
    const std::string s = report::summaryMarkdown(run, "https://ci.example.org/r/index.html");
    // Two kernels x two checks; hemisphere's RMSE is ten times its tolerance,
    // alchemy's barely over, and max abs error is 5x for both.
    const size_t hemiRmse = s.find("| `hemisphere` | RMSE (ao) | 1 (gl+vk) |");
    const size_t alchemyRmse = s.find("| `alchemy` | RMSE (ao) | 2 (gl+vk) | RMSE 0.007");
    const size_t alchemyMax = s.find("| `alchemy` | max abs error (ao) | 2 (gl+vk) |");
    ASSERT_NE(hemiRmse, std::string::npos) << s;
    ASSERT_NE(alchemyRmse, std::string::npos) << s;
    ASSERT_NE(alchemyMax, std::string::npos) << s;
    EXPECT_LT(hemiRmse, alchemyMax) << s;
    EXPECT_LT(alchemyMax, alchemyRmse) << s;
    EXPECT_NE(s.find("[Full report](https://ci.example.org/r/index.html)"), std::string::npos) << s;
}

// Tolerances sized to each image's pixels differ between the rows a group
// counts: the row gives the worst one's limit and the range it spans.
TEST(Summary, AGroupHeldToSeveralLimitsSaysTheirRange) {
    GateRun run;
    run.matrix = "ci";
    ConfigResult small = failingResult("alchemy", 16, "vk", 0.006), large = failingResult("alchemy", 32, "vk", 0.004);
    small.images[0].failures = {"mean abs error 0.0002 > 6e-05"};
    large.images[0].failures = {"mean abs error 0.0001 > 1.5e-05"};
    run.results = {small, large};
    const std::string s = report::summaryMarkdown(run);
    EXPECT_NE(s.find("mean abs error 0.0001 at `corner/alchemy/n32/b4/full/160x90/compute` | ≤ 1.5e-05 "
                     "(1.5e-05 to 6e-05 across them) |"),
              std::string::npos)
        << s;
    run.results = {small};
    const std::string one = report::summaryMarkdown(run);
    EXPECT_NE(one.find("| ≤ 6e-05 |"), std::string::npos) << one;
}

// A failing card prints the commands that accept its configuration alone.
TEST(Summary, AFailureNamesTheCommandThatAcceptsItAlone) {
    const ConfigResult r = failingResult("alchemy", 16, "vk", 0.02);
    ASSERT_EQ(r.verdict(), "fail");
    const std::string note = report::verdictNote(r);
    EXPECT_NE(note.find("cavity baselines update --filter '^" + r.id + "$'"), std::string::npos) << note;
    EXPECT_NE(note.find("cavity baselines approve --filter '^" + r.id + "$'"), std::string::npos) << note;
}

}  // namespace
}  // namespace cavity::test
