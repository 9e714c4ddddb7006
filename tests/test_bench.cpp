// The benchmark runner: registers exactly the sweep's configurations, runs a
// filtered subset on both APIs, and reports as manual time exactly the GPU
// time the backend's timestamps gave for the passes after the G-buffer.
#include "pipeline/config_id.h"
#include "per_pass_reporter.h"
#include "run_binary.h"
#include "plan/sweep.h"

#include <gtest/gtest.h>
#include <algorithm>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using cavity::test::Outcome;

Outcome bench(const std::string& args) { return cavity::test::runBinary(CAVITY_BENCH_EXE, args); }

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
        const auto configs = cavity::plan::benchmarkSweep(sweep == "cpu" ? cavity::plan::cpuSweep() : cavity::plan::gpuSweep(),
                                                    {cavity::gpu::Api::OpenGL, cavity::gpu::Api::Vulkan});
        std::set<std::string> declared;
        const int w = sweep == "cpu" ? 320 : 1920, h = sweep == "cpu" ? 180 : 1080;
        const auto at = [](int x, int y) { return std::to_string(x) + "x" + std::to_string(y) + "/"; };
        const std::string size = at(w, h);
        // The empty chain also at twice the size and a half, a quarter and an
        // eighth of it (bench/overhead_probes.h), and under one scope.
        for (const std::string api : {"gl", "vk"})
            for (const auto& probe :
                 {std::string("empty_scope/"), "empty_chain/" + size, "store_chain/" + size, "empty_chain_one_scope/" + size,
                  "empty_chain/" + at(2 * w, 2 * h), "empty_chain/" + at(w / 2, h / 2), "empty_chain/" + at(w / 4, h / 4),
                  "empty_chain/" + at(w / 8, h / 8)})
                declared.insert("timer/" + probe + api);
        for (const auto& c : configs) declared.insert(cavity::pipeline::configId(c));
        if (!ci() && listed.size() + 16 < declared.size()) GTEST_SKIP() << "a backend is missing here";
        EXPECT_EQ(listed, declared) << sweep;
        EXPECT_GT(configs.size(), sweep == "gpu" ? 300u : 20u);
    }
}

nlohmann::json runBench(const std::string& args) {
    const fs::path out = fs::temp_directory_path() / ("cavity-bench-" + std::to_string(::getpid()) + ".json");
    const Outcome o = bench(args + " --benchmark_out=" + out.string() + " --benchmark_out_format=json");
    EXPECT_EQ(o.code, 0) << o.output;
    std::ifstream f(out);
    if (!f) return {};
    // Google Benchmark writes bare NaN for the cv of a constant counter;
    // nlohmann reads JSON only, so those become null first.
    std::string text((std::istreambuf_iterator<char>(f)), {});
    for (size_t at; (at = text.find(": NaN")) != std::string::npos;) text.replace(at, 5, ": null");
    for (size_t at; (at = text.find(": -nan")) != std::string::npos;) text.replace(at, 6, ": null");
    fs::remove(out);
    return nlohmann::json::parse(text);
}

bool mirror(const nlohmann::json& b) { return b["name"].get<std::string>().find('@') != std::string::npos; }

TEST(Bench, SmokeRunOnBothApisWithManualTimeFromTimestamps) {
    const auto doc = runBench("--frames 1 --warmup 1 --benchmark_filter='corner/alchemy/n16/b4/full/320x180/(gl|vk)/compute/'");
    ASSERT_TRUE(doc.contains("benchmarks"));
    std::set<std::string> apis;
    for (const auto& b : doc["benchmarks"]) {
        ASSERT_FALSE(b.value("error_occurred", false)) << b.dump();
        if (mirror(b)) continue;
        apis.insert(b["name"].get<std::string>().find("/gl/") != std::string::npos ? "gl" : "vk");
        // One frame: the manual time is that frame's AO + blur + composite
        // times, and each pass counter is its only sample.
        const double sum = b["pass_ao_ms"].get<double>() + b["pass_blur_ms"].get<double>() +
                           b["pass_composite_ms"].get<double>();
        EXPECT_NEAR(b["real_time"].get<double>(), sum, 1e-6 * sum) << b["name"];
        EXPECT_EQ(b["time_unit"], "ms");
        EXPECT_GT(b["MP/s"].get<double>(), 0.0);
        EXPECT_EQ(b["frames"].get<double>(), 1.0);
    }
    if (ci()) {
        EXPECT_EQ(apis.size(), 2u);
    }
    EXPECT_EQ(doc["context"]["cavity_sweep"], "cpu");
    EXPECT_TRUE(doc["context"].contains("cavity_timing_mode"));
    // A software renderer has no floor: the context says why, and no
    // floor counter stands in for one.
    const std::string floors = doc["context"]["cavity_floor_device"];
    EXPECT_NE(floors.find("no floor: software renderer ("), std::string::npos) << floors;
    for (const auto& b : doc["benchmarks"])
        for (const auto& [k, v] : b.items())
            EXPECT_TRUE(k.rfind("floor_", 0) != 0 && k.rfind("over_floor_", 0) != 0 && k != "floor_ms") << b["name"] << " " << k;
}

// A pass with a floor keeps it on its own entry: <id>@ao carries floor_ms
// and measured_over_floor from the run's floor_ao_ms and over_floor_ao, and
// a pass without one (blur here) carries neither.
TEST(Bench, PassEntriesCarryTheirFloor) {
    benchmark::BenchmarkReporter::Run run;
    run.run_name.function_name = "corner/alchemy/n16/b4/full/1920x1080/vk/compute";
    run.iterations = 1;
    run.real_accumulated_time = 1e-3;
    run.time_unit = benchmark::kMillisecond;
    run.counters["pass_ao_ms"] = 0.2;
    run.counters["pass_blur_ms"] = 0.6;
    run.counters["floor_ao_ms"] = 0.1388;
    run.counters["over_floor_ao"] = 1.44;
    std::ostringstream out, err;
    cavity::bench::PerPassJsonReporter reporter;
    reporter.SetOutputStream(&out);
    reporter.SetErrorStream(&err);
    reporter.ReportContext(benchmark::BenchmarkReporter::Context());
    reporter.ReportRuns({run});
    reporter.Finalize();
    const auto doc = nlohmann::json::parse(out.str());
    std::map<std::string, nlohmann::json> byName;
    for (const auto& b : doc["benchmarks"]) byName[b["name"]] = b;
    ASSERT_TRUE(byName.count(run.run_name.function_name + "@ao")) << out.str();
    const auto& ao = byName[run.run_name.function_name + "@ao"];
    EXPECT_DOUBLE_EQ(ao["floor_ms"].get<double>(), 0.1388);
    EXPECT_DOUBLE_EQ(ao["measured_over_floor"].get<double>(), 1.44);
    EXPECT_FALSE(ao.contains("floor_ao_ms"));
    const auto& blur = byName[run.run_name.function_name + "@blur"];
    EXPECT_FALSE(blur.contains("floor_ms")) << blur.dump();
    EXPECT_FALSE(blur.contains("measured_over_floor"));
    // The run itself keeps every counter.
    EXPECT_DOUBLE_EQ(byName[run.run_name.function_name]["floor_ao_ms"].get<double>(), 0.1388);
}

// Every repetition carries one clock for its configuration, and each pass
// appears as an entry of its own (<id>@<pass>) whose time is that pass's
// counter, so Google Benchmark's compare.py sees every pass.
TEST(Bench, RepetitionsShareOneClockAndEveryPassHasAnEntry) {
    const auto doc = runBench("--frames 2 --warmup 0 --benchmark_repetitions=3 "
                              "--benchmark_filter='corner/alchemy/n16/b4/full/320x180/(gl|vk)/compute/'");
    ASSERT_TRUE(doc.contains("benchmarks"));
    std::map<std::string, std::set<std::string>> clocks;   // run name -> clock words seen
    std::map<std::string, double> counters;                // "<run name> <pass> <repetition>" -> ms
    std::map<std::string, double> mirrors;
    for (const auto& b : doc["benchmarks"]) {
        if (b["run_type"] != "iteration") continue;
        const std::string name = b["run_name"], label = b.value("label", "");
        const std::string rep = std::to_string(b["repetition_index"].get<int>());
        ASSERT_EQ(label.rfind("clock=", 0), 0u) << label;
        if (mirror(b)) {
            const auto at = name.find('@'), slash = name.find('/', at);
            const std::string base = name.substr(0, at) + name.substr(slash);
            mirrors[base + " " + name.substr(at + 1, slash - at - 1) + " " + rep] = b["real_time"];
            continue;
        }
        clocks[name].insert(label.substr(6, label.find(' ') - 6));
        for (const auto& [k, v] : b.items())
            if (k.rfind("pass_", 0) == 0) counters[name + " " + k.substr(5, k.size() - 8) + " " + rep] = v;
    }
    ASSERT_FALSE(clocks.empty());
    for (const auto& [name, seen] : clocks) EXPECT_EQ(seen.size(), 1u) << name << " mixes clocks";
    ASSERT_FALSE(counters.empty());
    EXPECT_EQ(mirrors.size(), counters.size());
    for (const auto& [key, ms] : counters) {
        ASSERT_TRUE(mirrors.count(key)) << key;
        EXPECT_NEAR(mirrors[key], ms, 1e-9 + 1e-9 * ms) << key;
    }
}

// The console: a line per configuration with every pass, the repetitions'
// median and spread, no "nan" anywhere, and the library's DEBUG warning
// replaced by what it means.
TEST(Bench, ConsoleIsATableWithoutNan) {
    const Outcome o = bench("--benchmark_filter='corner/alchemy/n16/b4/half/320x180/vk/compute' --frames 3 --warmup 1 "
                            "--benchmark_repetitions=3");
    ASSERT_EQ(o.code, 0) << o.output;
    std::string lower = o.output;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    EXPECT_EQ(lower.find("nan"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("***WARNING***"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("median of 3:"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("[cv "), std::string::npos) << o.output;
    int rows = 0;
    std::istringstream lines(o.output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("corner/alchemy/n16/b4/half/320x180/vk/compute  ", 0) == 0) {
            ++rows;
            for (const char* pass : {" ao ", " blur ", " composite ", " upsample ", " frames, clock="})
                EXPECT_NE(line.find(pass), std::string::npos) << line;
            EXPECT_LT(line.size(), 220u) << line;
        }
    EXPECT_EQ(rows, 3);
}

// The overhead probes (bench/overhead_probes.h) on both APIs, with the
// barriers off: the run says so in its context, and a pass that stores
// 320x180 texels reads longer than a timestamp pair with nothing between.
TEST(Bench, OverheadProbesRunAndRecordTheBarrierSwitch) {
    const fs::path out = fs::temp_directory_path() / ("cavity-probes-" + std::to_string(::getpid()) + ".json");
    const Outcome o = cavity::test::runBinary(CAVITY_BENCH_EXE, "--benchmark_filter='^timer/' --benchmark_out=" +
                                                                    out.string() + " --benchmark_out_format=json",
                                              "CAVITY_NO_BARRIERS=1");
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(out);
    const auto doc = nlohmann::json::parse(f);
    fs::remove(out);
    EXPECT_EQ(doc["context"]["cavity_env_CAVITY_NO_BARRIERS"], "1");
    std::map<std::string, double> us;
    for (const auto& b : doc["benchmarks"]) us[b["name"].get<std::string>().substr(0, b["name"].get<std::string>().find("/iterations"))] = b["median_us"];
    for (const std::string api : {"gl", "vk"}) {
        if (!ci() && !us.count("timer/empty_scope/" + api)) continue;   // a backend missing here
        ASSERT_TRUE(us.count("timer/store_chain/320x180/" + api)) << o.output;
        EXPECT_GT(us["timer/store_chain/320x180/" + api], us["timer/empty_scope/" + api]) << api;
        EXPECT_GT(us["timer/empty_chain/320x180/" + api], 0.0) << api;
    }
    EXPECT_NE(o.output.find("us a pass"), std::string::npos) << o.output;
}

// The barrier switches are 0 or 1, and not both: anything else stops the
// run with one line that names the variable.
TEST(Bench, BarrierSwitchesAreCheckedBeforeAnything) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"CAVITY_NO_BARRIERS=yes", "cavity_bench: CAVITY_NO_BARRIERS=yes: must be 0 or 1"},
        {"CAVITY_FULL_BARRIERS=2", "cavity_bench: CAVITY_FULL_BARRIERS=2: must be 0 or 1"},
        {"CAVITY_NO_BARRIERS=1 CAVITY_FULL_BARRIERS=1", "cavity_bench: CAVITY_FULL_BARRIERS and CAVITY_NO_BARRIERS: set one"}};
    for (const auto& [env, message] : cases) {
        const Outcome o = cavity::test::runBinary(CAVITY_BENCH_EXE, "--benchmark_filter='^timer/empty_scope'", env);
        EXPECT_EQ(o.code, 2) << env << ": " << o.output;
        EXPECT_EQ(o.output.rfind(message, 0), 0u) << env << ": " << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    }
}

TEST(Bench, BadFlagIsAnError) {
    const Outcome o = bench("--sweep huge --benchmark_list_tests");
    EXPECT_EQ(o.code, 2) << o.output;
    EXPECT_NE(o.output.find("--sweep 'huge': must be gpu, cpu or auto"), std::string::npos) << o.output;
    for (const std::string bad : {"--frames 0", "--frames abc", "--frames -3", "--warmup abc", "--device abc",
                                  "--max-noise nan", "--max-time 1e999", "--timing hot", "--plant ao:0", "--plant ao"}) {
        const Outcome b = bench(bad + " --benchmark_list_tests");
        EXPECT_EQ(b.code, 2) << bad << ": " << b.output;
        EXPECT_NE(b.output.find(bad.substr(0, bad.find(' '))), std::string::npos) << b.output;
    }
    const Outcome none = bench("--benchmark_filter=nothing-matches-this");
    EXPECT_EQ(none.code, 2) << none.output;
}

}  // namespace
