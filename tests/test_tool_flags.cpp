// cavity_bench's and cavity_render's own flags, declared once and parsed by
// CLI11 as cavity's are (cli/flags.h): --help on stdout with exit 0, an
// unknown flag named with its nearest neighbour, one-line errors with exit 2.
#include "kernel.h"
#include "run_binary.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using cavity::test::runBinary;

struct Tool {
    std::string name, path;
};

const std::vector<Tool>& tools() {
    static const std::vector<Tool> t = {{"cavity_bench", CAVITY_BENCH_EXE}, {"cavity_render", CAVITY_RENDER_EXE}};
    return t;
}

TEST(ToolFlags, HelpPrintsOnStdoutAndExitsZero) {
    for (const auto& t : tools()) {
        for (const char* h : {"--help", "-h"}) {
            const auto o = runBinary(t.path, h, "", "2>/dev/null");
            EXPECT_EQ(o.code, 0) << t.name << " " << h << "\n" << o.output;
            EXPECT_NE(o.output.find("Usage: " + t.name), std::string::npos) << t.name << "\n" << o.output;
        }
        // Help wins wherever it stands, even after a bad value.
        EXPECT_EQ(runBinary(t.path, "--device abc --help").code, 0) << t.name;
    }
}

// Text with every run of spaces and line breaks as one space: --help wraps
// its lines at 100 columns, so a summary may span two of them.
std::string oneLine(const std::string& text) { return std::regex_replace(text, std::regex(R"(\s+)"), " "); }

// --version names the commit the binary was built from, as git names the
// checkout's HEAD, so that a result or a report can name its binary.
TEST(ToolFlags, VersionNamesTheCommitAndTheBuildType) {
    const auto head = runBinary("git", std::string("-C ") + CAVITY_SOURCE_DIR + " rev-parse --short=12 HEAD", "",
                                "2>/dev/null");
    for (const auto& [name, path] : std::vector<std::pair<std::string, std::string>>{
             {"cavity", CAVITY_EXE}, {"cavity_render", CAVITY_RENDER_EXE}, {"cavity_bench", CAVITY_BENCH_EXE}}) {
        const auto o = runBinary(path, "--version");
        EXPECT_EQ(o.code, 0) << name;
        std::smatch m;
        ASSERT_TRUE(std::regex_match(o.output, m, std::regex(name + " (\\S+) \\((.+)\\)\n"))) << o.output;
        // Built from a git checkout (CI's clone is one): its HEAD, or its
        // HEAD marked dirty; a source tree without git says so.
        if (head.code == 0 && head.output.size() >= 12) {
            EXPECT_EQ(m[1].str().substr(0, 12), head.output.substr(0, 12)) << o.output;
        }
        EXPECT_FALSE(m[2].str().empty());
    }
}

TEST(ToolFlags, BenchHelpNamesEveryFlagAndEveryKernelWithItsSummary) {
    const auto o = runBinary(CAVITY_BENCH_EXE, "--help", "", "2>/dev/null");
    ASSERT_EQ(o.code, 0);
    const std::string help = oneLine(o.output);
    for (const char* f : {"--backend", "--sweep", "--frames", "--warmup", "--timing", "--max-noise", "--max-time",
                          "--plant", "--plant-file", "--device", "--benchmark_filter"})
        EXPECT_NE(o.output.find(f), std::string::npos) << f;
    for (const auto& k : cavity::kernels::all()) {
        if (k.role != cavity::kernels::Role::Ao && k.role != cavity::kernels::Role::Reference) continue;
        EXPECT_NE(help.find(oneLine(k.summary)), std::string::npos) << k.name;
    }
}

// Examples unwrapped, one line each (test_cli.cpp says why).
TEST(ToolFlags, HelpWrapsAt100ColumnsAndEndsWithUnwrappedExamples) {
    for (const std::string tool : {CAVITY_BENCH_EXE, CAVITY_RENDER_EXE}) {
        const auto o = runBinary(tool, "--help", "", "2>/dev/null");
        ASSERT_EQ(o.code, 0) << tool;
        std::istringstream lines(o.output);
        std::string line, last;
        bool inExamples = false;
        while (std::getline(lines, line)) {
            if (line == "Examples:") {
                inExamples = true;
            } else if (inExamples && !line.empty()) {
                EXPECT_EQ(line.rfind("  cavity_", 0), 0u) << tool << ": an example wrapped: " << line;
            } else if (!inExamples) {
                EXPECT_LE(line.size(), 100u) << tool << ": " << line;
            }
            EXPECT_EQ(line.find(" ..."), std::string::npos) << tool << ": a parser leftover: " << line;
            if (!line.empty()) last = line;
        }
        EXPECT_NE(o.output.find("\nExamples:\n"), std::string::npos) << tool;
        EXPECT_EQ(last.rfind("  cavity_", 0), 0u) << tool << ": ends with " << last;
    }
}

TEST(ToolFlags, RenderHelpNamesEveryFlag) {
    const auto o = runBinary(CAVITY_RENDER_EXE, "--help", "", "2>/dev/null");
    ASSERT_EQ(o.code, 0);
    for (const char* f : {"--matrix", "--out", "--baselines", "--backend", "--shard", "--device", "--filter", "--repeat",
                          "--validation", "--timing", "--max-noise", "--max-time", "--kernel-source"})
        EXPECT_NE(o.output.find(f), std::string::npos) << f;
}

// The flags --help prints, as the docs name them.
std::set<std::string> helpFlags(const std::string& help) {
    std::set<std::string> flags;
    const std::regex flag(R"(\n  (--[a-z-]+))");
    for (auto it = std::sregex_iterator(help.begin(), help.end(), flag); it != std::sregex_iterator(); ++it)
        flags.insert((*it)[1].str());
    flags.erase("--help");
    return flags;
}

// The text of a docs/ page between two markers (empty when either is missing).
std::string docSection(const std::string& page, const std::string& from, const std::string& to) {
    std::ifstream f(std::string(CAVITY_SOURCE_DIR) + "/docs/" + page);
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const size_t a = text.find(from), b = text.find(to, a);
    return a == std::string::npos || b == std::string::npos ? "" : text.substr(a, b - a);
}

TEST(ToolFlags, DocsNameEveryFlagHelpPrints) {
    const std::string bench = docSection("benchmarking.md", "- Own flags:", "a `--benchmark_filter` that matches");
    const std::string render = docSection("gate.md", "    cavity_render --matrix NAME", "    cavity gate judge RENDER_DIR");
    ASSERT_FALSE(bench.empty());
    ASSERT_FALSE(render.empty());
    const auto benchFlags = helpFlags(runBinary(CAVITY_BENCH_EXE, "--help", "", "2>/dev/null").output);
    const auto renderFlags = helpFlags(runBinary(CAVITY_RENDER_EXE, "--help", "", "2>/dev/null").output);
    EXPECT_GE(benchFlags.size(), 10u);
    EXPECT_GE(renderFlags.size(), 12u);
    for (const auto& f : benchFlags)
        EXPECT_NE(bench.find("`" + f), std::string::npos) << f << ": not in docs/benchmarking.md, \"Own flags\"";
    for (const auto& f : renderFlags) EXPECT_NE(render.find(f), std::string::npos) << f << ": not in docs/gate.md's cavity_render usage";
}

struct BadCase {
    std::string tool, args, line;   // the one line expected, whole
};

TEST(ToolFlags, BadInputIsOneLineNamingTheFlagAndExitsTwo) {
    const std::string bench = CAVITY_BENCH_EXE, render = CAVITY_RENDER_EXE;
    const std::vector<BadCase> cases = {
        {bench, "--framse 3", "cavity_bench: --framse: unknown flag (did you mean --frames? see cavity_bench --help)"},
        {bench, "--sweeep cpu", "cavity_bench: --sweeep: unknown flag (did you mean --sweep? see cavity_bench --help)"},
        {bench, "--half", "cavity_bench: --half: unknown flag (see cavity_bench --help)"},
        {bench, "--frames", "cavity_bench: --frames: missing value (--frames N)"},
        {bench, "--frames 3 --frames 4",
         "cavity_bench: --frames: given twice (give one value, or one comma-separated list where the flag takes a list)"},
        {bench, "--device ''", "cavity_bench: --device '': empty value (--device K)"},
        {bench, "--iterations 0", "cavity_bench: --iterations 0: must be an integer in 1..1000000"},
        {bench, "--sweep moon", "cavity_bench: --sweep 'moon': must be gpu, cpu or auto"},
        {render, "--matirx ci --out x", "cavity_render: --matirx: unknown flag (did you mean --matrix? see cavity_render --help)"},
        {render, "--repeat 0 --matrix ci --out x", "cavity_render: --repeat 0: must be an integer in 1..1000"},
        {render, "--matrix", "cavity_render: --matrix: missing value (--matrix NAME)"},
        // The baselines are the repository's, found without --baselines (the
        // test runs inside the build tree, below the source tree).
        {render, "--out x", "cavity_render: --matrix: missing (name a matrix of " + std::string(CAVITY_SOURCE_DIR) +
                                "/baselines/matrices.json)"},
        {render, "stray --matrix ci --out x", "cavity_render: 'stray': unexpected argument (flags start with --; see cavity_render --help)"},
    };
    for (const auto& c : cases) {
        const auto o = runBinary(c.tool, c.args);
        EXPECT_EQ(o.code, 2) << c.tool << " " << c.args << "\n" << o.output;
        EXPECT_EQ(o.output, c.line + "\n") << c.tool << " " << c.args;
    }
}

TEST(ToolFlags, RenderTakesKernelSourceMoreThanOnce) {
    // Repeatable: both are read (the second names no kernel source, and says so).
    const std::string file = std::string(CAVITY_SOURCE_DIR) + "/kernels/ao/alchemy/ssao_alchemy.glsl";
    const auto o = runBinary(CAVITY_RENDER_EXE,
                             "--matrix ci --out x --kernel-source ssao_alchemy.glsl=" + file + " --kernel-source nope.glsl=" + file);
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_EQ(o.output, "cavity_render: --kernel-source nope.glsl: no kernel source of that name (a .glsl file under kernels/ or in a --kernels package)\n");
}

}  // namespace
