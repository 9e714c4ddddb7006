// The benchmark runner: registers exactly the sweep's configurations, runs a
// filtered subset on both APIs, and reports as manual time exactly the GPU
// time the backend's timestamps gave for the passes after the G-buffer.
#include "sweep.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace {

struct Outcome {
    int code = -1;
    std::string output;
};

Outcome bench(const std::string& args) {
    const std::string cmd = std::string(CAVITY_BENCH_EXE) + " " + args + " 2>&1";
    Outcome o;
    FILE* p = popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) o.output.append(buf.data(), n);
    const int status = pclose(p);
    o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return o;
}

bool ci() {
    const char* v = std::getenv("CI");
    return v && std::string(v) == "true";
}

TEST(Bench, RegistersExactlyTheDeclaredSweep) {
    for (const std::string sweep : {"cpu", "gpu"}) {
        const Outcome o = bench("--sweep " + sweep + " --benchmark_list_tests");
        ASSERT_EQ(o.code, 0) << o.output;
        std::set<std::string> listed;
        std::istringstream lines(o.output);
        for (std::string line; std::getline(lines, line);)
            if (line.find("/iterations:") != std::string::npos) listed.insert(line.substr(0, line.find("/iterations:")));
        const auto configs = cavity::benchmarkSweep(sweep == "cpu" ? cavity::cpuSweep() : cavity::gpuSweep(),
                                                    {cavity::gpu::Api::OpenGL, cavity::gpu::Api::Vulkan});
        std::set<std::string> declared{"timer/empty_scope/gl", "timer/empty_scope/vk"};
        for (const auto& c : configs) declared.insert(cavity::configId(c));
        if (!ci() && listed.size() + 2 < declared.size()) GTEST_SKIP() << "a backend is missing here";
        EXPECT_EQ(listed, declared) << sweep;
        EXPECT_GT(configs.size(), sweep == "gpu" ? 300u : 20u);
    }
}

TEST(Bench, SmokeRunOnBothApisWithManualTimeFromTimestamps) {
    const fs::path out = fs::temp_directory_path() / ("cavity-bench-" + std::to_string(::getpid()) + ".json");
    const Outcome o = bench("--iterations 1 --warmup 1 --benchmark_filter='corner/alchemy/n16/b4/full/320x180/(gl|vk)/compute'"
                            " --benchmark_out=" + out.string() + " --benchmark_out_format=json");
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(out);
    const auto doc = nlohmann::json::parse(f);
    fs::remove(out);
    std::set<std::string> apis;
    for (const auto& b : doc["benchmarks"]) {
        ASSERT_FALSE(b.value("error_occurred", false)) << b.dump();
        apis.insert(b["name"].get<std::string>().find("/gl/") != std::string::npos ? "gl" : "vk");
        // One iteration: the manual time is that frame's AO + blur + composite
        // timestamps, and each pass counter is its only sample.
        const double sum = b["pass_ao_ms"].get<double>() + b["pass_blur_ms"].get<double>() +
                           b["pass_composite_ms"].get<double>();
        EXPECT_NEAR(b["real_time"].get<double>(), sum, 1e-6 * sum) << b["name"];
        EXPECT_EQ(b["time_unit"], "ms");
        EXPECT_GT(b["MP/s"].get<double>(), 0.0);
    }
    if (ci()) {
        EXPECT_EQ(apis.size(), 2u);
    }
    EXPECT_EQ(doc["context"]["cavity_sweep"], "cpu");
}

TEST(Bench, BadFlagIsAnError) {
    const Outcome o = bench("--sweep huge --benchmark_list_tests");
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find("--sweep huge: must be gpu, cpu or auto"), std::string::npos) << o.output;
}

}  // namespace
