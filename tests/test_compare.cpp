// `cavity compare` as a pull request meets it: two runs with a known change,
// in both file formats, and the verdicts, intervals, exit codes and
// one-line errors that come out. No GPU: every input is fabricated here.
#include "run_binary.h"
#include "core/json_file.h"
#include "compare/sample_sets.h"
#include "compare/compare_verdict.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <sys/wait.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using ::cavity::test::Outcome;

Outcome cavity(const std::string& args) {
    return ::cavity::test::runBinary(CAVITY_EXE, args);
}

// Deterministic noise in [-1, 1), so that every run of the test sees the same samples.
struct Noise {
    uint64_t state;
    double next() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) / 4503599627370496.0 - 1.0;
    }
};

// One configuration of a fabricated run: per repetition (or frame), each
// pass's time and the clock that took it.
struct FakeConfig {
    std::string id;
    std::map<std::string, std::vector<double>> passMs;
    std::vector<std::string> clocks;   // one per repetition
    double smMhz = NAN;                 // the SM clock NVML read, where it did
};

// Base times of the fabricated alchemy pipeline, ms.
const std::map<std::string, double> kBase = {{"ao", 0.6}, {"blur", 0.3}, {"composite", 0.1}};
const std::string kId = "corner/alchemy/n16/b4/full/1920x1080/vk/compute";
const std::string kOtherId = "slats/alchemy/n16/b4/full/1920x1080/vk/compute";

// `count` samples of each pass around kBase, with noise of up to a hundredth of it from `seed`, and
// `aoShift` (in ms) added to the AO pass.
FakeConfig fakeConfig(const std::string& id, size_t count, uint64_t seed, double aoShift,
                      const std::string& clock = "gpu-timestamp") {
    FakeConfig c{id, {}, std::vector<std::string>(count, clock)};
    Noise noise{seed};
    for (const auto& [pass, base] : kBase)
        for (size_t i = 0; i < count; ++i)
            c.passMs[pass].push_back(base * (1 + 0.01 * noise.next()) + (pass == "ao" ? aoShift : 0));
    return c;
}

double pipelineMs(const FakeConfig& c, size_t rep) {
    double sum = 0;
    for (const auto& [pass, ms] : c.passMs) sum += ms[rep];
    return sum;
}

// Google Benchmark JSON as cavity_bench writes it with --benchmark_repetitions:
// the iteration entries (real_time in microseconds here, to exercise the
// unit), then the mean, median, stddev and cv aggregates, whose constant
// counters are 0/0 and come out as a bare NaN.
std::string benchmarkJson(const std::vector<FakeConfig>& configs, bool withErrorAndMirrors = false,
                          bool softwareRenderer = false) {
    json benchmarks = json::array();
    for (const auto& c : configs) {
        const std::string name = c.id + "/iterations:50/manual_time";
        const size_t reps = c.clocks.size();
        auto entry = [&](const std::string& entryName, const std::string& runType) {
            return json{{"name", entryName},         {"family_index", 0}, {"per_family_instance_index", 0},
                        {"run_name", name},          {"run_type", runType}, {"repetitions", reps},
                        {"threads", 1},              {"iterations", 50},  {"time_unit", "us"},
                        {"width", 1920.0},           {"height", 1080.0},  {"samples", 16.0}};
        };
        for (size_t r = 0; r < reps; ++r) {
            json e = entry(name, "iteration");
            e["repetition_index"] = r;
            e["real_time"] = 1000.0 * pipelineMs(c, r);
            e["cpu_time"] = 1300.0;
            for (const auto& [pass, ms] : c.passMs) e["pass_" + pass + "_ms"] = ms[r];
            if (std::isfinite(c.smMhz)) {
                e["sm_mhz_min"] = e["sm_mhz_median"] = e["sm_mhz_max"] = c.smMhz;
                e["mem_mhz_median"] = 3201.0;
            }
            e["label"] = "clock=" + c.clocks[r] + (c.clocks[r] == "wall" ? " (timestamps do not bracket the work)"
                                                                          : " mode=batch");
            benchmarks.push_back(e);
            if (withErrorAndMirrors)   // cavity_bench's per-pass mirror for compare.py: same numbers again
                for (const auto& [pass, ms] : c.passMs) {
                    json m = e;
                    m["name"] = m["run_name"] = c.id + "@" + pass + "/iterations:50/manual_time";
                    m["real_time"] = 1000.0 * ms[r];
                    benchmarks.push_back(m);
                }
        }
        for (const char* aggregate : {"mean", "median", "stddev", "cv"}) {
            json e = entry(name + "_" + aggregate, "aggregate");
            e["aggregate_name"] = aggregate;
            e["real_time"] = 1.0;
            const std::string a = aggregate;
            e["samples"] = a == "cv" ? json("@NAN@") : a == "stddev" ? json("@INF@") : json(16.0);
            e["label"] = "clock=" + c.clocks[0];
            benchmarks.push_back(e);
        }
    }
    if (withErrorAndMirrors)
        benchmarks.push_back({{"name", kOtherId + "/iterations:50/manual_time"},
                              {"run_name", kOtherId + "/iterations:50/manual_time"},
                              {"run_type", "iteration"},
                              {"error_occurred", true},
                              {"error_message", "vkCreateImage: VK_ERROR_OUT_OF_DEVICE_MEMORY"},
                              {"real_time", 0.0},
                              {"time_unit", "us"}});
    const json doc = {{"context", {{"date", "2026-12-01T10:00:00+00:00"}, {"cavity_sweep", "gpu"},
                                   {"cavity_software_renderer", softwareRenderer ? "true" : "false"}}},
                      {"benchmarks", benchmarks}};
    std::string text = doc.dump(2);
    // Google Benchmark's own spelling of 0/0 and of an overflow.
    for (auto [from, to] : {std::pair<std::string, std::string>{"\"@NAN@\"", "NaN"}, {"\"@INF@\"", "Infinity"}})
        for (size_t at; (at = text.find(from)) != std::string::npos;) text.replace(at, from.size(), to);
    return text;
}

// results.json (cavity.results/1) with one sample per frame.
std::string resultsJson(const std::vector<FakeConfig>& configs) {
    json runs = json::array();
    for (const auto& c : configs) {
        json passes = json::array();
        std::vector<double> frame;
        for (size_t r = 0; r < c.clocks.size(); ++r) frame.push_back(0.05 + pipelineMs(c, r));
        for (const char* pass : {"gbuffer", "ao", "blur", "composite"}) {
            const auto it = c.passMs.find(pass);
            passes.push_back({{"name", pass},
                              {"samples_ms", it == c.passMs.end() ? std::vector<double>(c.clocks.size(), 0.05)
                                                                  : it->second},
                              {"stats", {{"median_ms", 0.0}}}});
        }
        runs.push_back({{"id", c.id}, {"backend", "vk"}, {"clock", c.clocks[0]}, {"passes", passes},
                        {"frame", {{"samples_ms", frame}, {"stats", {{"median_ms", 0.0}}}}}});
        runs.back()["gpu_clocks"] =
            std::isfinite(c.smMhz) ? json{{"source", "nvml"}, {"sm_mhz", {{"min", c.smMhz}, {"median", c.smMhz}, {"max", c.smMhz}}}}
                                   : json();
    }
    return json{{"schema", "cavity.results/1"}, {"runs", runs}}.dump(2);
}

class Compare : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("cavity-compare-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    }
    json rowsOf(const std::string& jsonPath) {
        std::ifstream f(jsonPath);
        const json doc = json::parse(f);
        EXPECT_EQ(doc["schema"], "cavity.compare/1");
        return doc["rows"];
    }
    static const json& row(const json& rows, const std::string& id, const std::string& pass) {
        for (const auto& r : rows)
            if (r["id"] == id && r["pass"] == pass) return r;
        static const json none;
        ADD_FAILURE() << "no row " << id << " " << pass;
        return none;
    }
    fs::path dir;
};

// ---- reading the files ----

TEST(CompareInput, NonFiniteTokensBecomeNullOutsideStrings) {
    EXPECT_EQ(cavity::core::nullNonFiniteTokens(R"({"cv": NaN, "a": -Infinity, "b": inf, "c": -inf, "d": [Infinity,nan]})"),
              R"({"cv": null, "a": null, "b": null, "c": null, "d": [null,null]})");
    // Inside strings, and as parts of other words, nothing changes.
    const std::string kept = R"({"label": "NaN Infinity \" inf", "infinity_count": 1e5, "x": null, "nanite": true})";
    EXPECT_EQ(cavity::core::nullNonFiniteTokens(kept), kept);
}

TEST(CompareInput, ConfigurationIdAndClockFromTheBenchmarkEntry) {
    EXPECT_EQ(cavity::compare::configurationIdOf(kId + "/iterations:50/manual_time"), kId);
    EXPECT_EQ(cavity::compare::configurationIdOf(kId + "/min_time:0.500/repeats:5/threads:1/real_time"), kId);
    EXPECT_EQ(cavity::compare::configurationIdOf(kId), kId);
    EXPECT_EQ(cavity::compare::clockOfLabel("clock=gpu-timestamp mode=batch"), "gpu-timestamp");
    EXPECT_EQ(cavity::compare::clockOfLabel("clock=wall (timestamps do not bracket the work)"), "wall");
    EXPECT_EQ(cavity::compare::clockOfLabel("mode=batch clock=wall"), "wall");
    EXPECT_EQ(cavity::compare::clockOfLabel(""), "unknown");
}

TEST_F(Compare, BenchmarkJsonGivesOneSamplePerRepetitionInMilliseconds) {
    const auto c = fakeConfig(kId, 6, 1, 0);
    const auto sets = cavity::compare::loadSampleSets(write("bench.json", benchmarkJson({c}, true)));
    ASSERT_TRUE(sets.ok()) << sets.error().message;
    EXPECT_EQ(sets->format, "google-benchmark");
    EXPECT_EQ(sets->skippedErrors, 1);
    EXPECT_EQ(sets->skippedMirrors, 6 * 3);
    const auto& pipeline = sets->series.at({kId, "pipeline"});
    ASSERT_EQ(pipeline.ms.size(), 6u);   // the aggregates are not samples
    EXPECT_NEAR(pipeline.ms[2], pipelineMs(c, 2), 1e-12);
    EXPECT_EQ(pipeline.clock, "gpu-timestamp");
    EXPECT_EQ(sets->series.at({kId, "ao"}).ms, c.passMs.at("ao"));
    EXPECT_EQ(sets->series.size(), 4u);   // pipeline and three passes; no series from the errored entry
}

// ---- the verdicts ----

TEST_F(Compare, KnownShiftIsSlowerAndTheRestIsSame) {
    // Ten repetitions each; the new run's AO pass is slower by a twentieth of
    // its base time, blur is the very same numbers, composite is fresh noise around the same time.
    const auto before = fakeConfig(kId, 10, 1, 0);
    auto after = fakeConfig(kId, 10, 2, 0.03);
    after.passMs["blur"] = before.passMs.at("blur");
    const std::string o = write("old.json", benchmarkJson({before}, true));
    const std::string n = write("new.json", benchmarkJson({after}));
    const std::string out = (dir / "verdicts.json").string();
    const Outcome r = cavity("compare " + o + " " + n + " --json " + out);
    ASSERT_EQ(r.code, 0) << r.output;   // slower, but not asked to fail on it
    const json rows = rowsOf(out);
    ASSERT_EQ(rows.size(), 4u);

    const json& ao = row(rows, kId, "ao");
    EXPECT_EQ(ao["verdict"], "slower") << ao.dump();
    EXPECT_EQ(ao["n_old"], 10);
    EXPECT_EQ(ao["n_new"], 10);
    EXPECT_LT(ao["p"].get<double>(), 0.001);
    EXPECT_EQ(ao["method"], "asymptotic");
    // The interval holds the true shift, in ms and as a share of the old median.
    EXPECT_LE(ao["ci_low_ms"].get<double>(), 0.03);
    EXPECT_GE(ao["ci_high_ms"].get<double>(), 0.03);
    const double truePct = 100 * 0.03 / ao["old_median_ms"].get<double>();
    EXPECT_LE(ao["ci_low_pct"].get<double>(), truePct);
    EXPECT_GE(ao["ci_high_pct"].get<double>(), truePct);
    EXPECT_NEAR(ao["change_pct"].get<double>(), 5.0, 1.0);
    EXPECT_GT(ao["ci_low_pct"].get<double>(), 0);

    // The pipeline carries the same shift, a smaller share of its longer time
    // but still over --min-change.
    EXPECT_EQ(row(rows, kId, "pipeline")["verdict"], "slower");
    const json& blur = row(rows, kId, "blur");
    EXPECT_EQ(blur["verdict"], "same");
    EXPECT_EQ(blur["shift_ms"].get<double>(), 0.0);
    EXPECT_NEAR(blur["p"].get<double>(), 1.0, 1e-12);
    EXPECT_EQ(row(rows, kId, "composite")["verdict"], "same");

    // The table: one line per row, every column lined up under its header.
    EXPECT_NE(r.output.find("1 errored entry"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 slower, 0 faster, 2 same"), std::string::npos) << r.output;
    const size_t header = r.output.find("\nconfiguration") + 1;
    ASSERT_NE(header, 0u) << r.output;
    const size_t verdictColumn = r.output.find("verdict", header) - header;
    size_t lines = 0;
    for (size_t at = r.output.find(kId); at != std::string::npos; at = r.output.find(kId, at + 1), ++lines) {
        const size_t lineStart = r.output.rfind('\n', at) + 1;
        const std::string line = r.output.substr(lineStart, r.output.find('\n', at) - lineStart);
        EXPECT_GE(line.size(), verdictColumn) << line;
        const std::string verdict = line.substr(verdictColumn);
        EXPECT_TRUE(verdict == "slower" || verdict == "same") << "'" << line << "'";
    }
    EXPECT_EQ(lines, 4u) << r.output;

    // And a pull request can gate on it.
    EXPECT_EQ(cavity("compare " + o + " " + n + " --fail-on-slower").code, 1);
    // An unchanged run (another file of the same samples) passes; one file
    // given as both runs compares nothing and is refused.
    const std::string same = write("old_again.json", benchmarkJson({before}, true));
    EXPECT_EQ(cavity("compare " + o + " " + same + " --fail-on-slower").code, 0);
    EXPECT_EQ(cavity("compare " + o + " " + o + " --fail-on-slower").code, 2);
    // A faster change is symmetric: swap the files.
    const Outcome back = cavity("compare " + n + " " + o + " --json " + out + " --fail-on-slower");
    EXPECT_EQ(back.code, 0) << back.output;
    EXPECT_EQ(row(rowsOf(out), kId, "ao")["verdict"], "faster");
    // The same shift under --min-change 10 is not worth a verdict.
    EXPECT_EQ(cavity("compare " + o + " " + n + " --min-change 10 --fail-on-slower").code, 0);
}

// The detectable change, by hand: the smallest difference between two
// distinct samples is the timer's step, and no change under it (or under the
// interval's half-width) can be called.
TEST(CompareVerdict, DetectableChangeIsTheIntervalOrTheTimersStep) {
    using cavity::compare::compareSeries;
    EXPECT_DOUBLE_EQ(cavity::compare::smallestStep({1.0, 1.25, 2.0}, {1.5}), 0.25);
    EXPECT_TRUE(std::isnan(cavity::compare::smallestStep({1.0, 1.0}, {1.0})));
    cavity::compare::SampleSet a, b;
    for (double v : {1.0, 1.0, 1.0, 1.1, 1.1}) a.add(v, "gpu-timestamp");
    for (double v : {1.0, 1.0, 1.1, 1.1, 1.1}) b.add(v, "gpu-timestamp");
    cavity::compare::CompareThresholds t;   // the default --min-change
    const auto r = compareSeries("x", "ao", &a, &b, t);
    EXPECT_NEAR(r.timerStepPct, 10.0, 1e-9);   // the samples' step over their median, a tenth
    EXPECT_GE(r.detectablePct, 10.0 - 1e-9);
    EXPECT_NEAR(r.detectablePct, std::max(10.0, (r.highPct - r.lowPct) / 2), 1e-9);
    EXPECT_EQ(r.verdict, "inconclusive");
    EXPECT_EQ(r.reason, "interval too wide");
    EXPECT_NE(r.next.find("more repetitions"), std::string::npos);
    // auto follows the detectable change up to --min-change: a timer this
    // coarse leaves the row inconclusive, never "same" at a threshold as
    // coarse as the timer.
    t.autoMinChange = true;
    const auto a2 = compareSeries("x", "ao", &a, &b, t);
    EXPECT_DOUBLE_EQ(a2.thresholdPct, 2.0);
    EXPECT_EQ(a2.verdict, "inconclusive");
    EXPECT_EQ(a2.reason, "interval too wide");
    // Identical constant samples: nothing to detect, the floor of auto is the threshold.
    cavity::compare::SampleSet c;
    for (int i = 0; i < 5; ++i) c.add(2.0, "gpu-timestamp");
    const auto same = compareSeries("x", "ao", &c, &c, t);
    EXPECT_EQ(same.verdict, "same");
    EXPECT_DOUBLE_EQ(same.detectablePct, 0.0);
    EXPECT_DOUBLE_EQ(same.thresholdPct, cavity::compare::kAutoFloorPct);
}

// --min-change auto never goes under kAutoFloorMs: on the H200 two processes
// of one build moved one of the shortest passes by two steps of GL's timer,
// every repetition of each on one value (study 2026-12-03_h200_sensitivity;
// the samples below are that pass's). That move is "same" on a pass that
// short, while the same share of a pass three times longer is a change, and
// the same move in time on that longer pass is not.
TEST(CompareVerdict, AutoThresholdIsNeverUnderTheDriftBetweenProcesses) {
    using cavity::compare::compareSeries;
    auto run = [](double ms, double jitter) {
        cavity::compare::SampleSet s;
        for (int i = 0; i < 10; ++i) s.add(ms + (i % 2) * jitter, "gpu-timestamp");
        return s;
    };
    cavity::compare::CompareThresholds t;
    t.autoMinChange = true;
    const auto shortA = run(0.013056, 0.0), shortB = run(0.013312, 0.0);
    const auto shortPass = compareSeries("x", "depth", &shortA, &shortB, t);
    EXPECT_NEAR(shortPass.changePct, 1.96, 0.01);
    EXPECT_DOUBLE_EQ(shortPass.thresholdPct, 2.0);   // kAutoFloorMs is over --min-change here; --min-change caps it
    EXPECT_EQ(shortPass.verdict, "same");
    // With jitter of one Vulkan timer step inside each process (constant samples
    // would make the shift itself the smallest step, the timer's).
    const auto longA = run(0.040, 0.000032), longB = run(0.040784, 0.000032), longDrift = run(0.040256, 0.000032);
    const auto longPass = compareSeries("x", "ao", &longA, &longB, t);
    EXPECT_NEAR(longPass.thresholdPct, 100 * 0.0003 / longPass.oldMedianMs, 1e-9);   // kAutoFloorMs over the old median
    EXPECT_EQ(longPass.verdict, "slower");
    EXPECT_EQ(compareSeries("x", "ao", &longA, &longDrift, t).verdict, "same");
    // A fixed --min-change is the user's: no floor is added to it.
    t.autoMinChange = false;
    t.minChangePct = 1.0;
    EXPECT_EQ(compareSeries("x", "depth", &shortA, &shortB, t).verdict, "slower");
}

// Samples so few that the U test cannot reach alpha give no verdict, however
// far apart: 3 against 3 reach p = 2 / C(6, 3) = 0.1 at best, and would
// otherwise read "same" for any change. 4 against 4: 2 / 70.
TEST(CompareVerdict, TooFewToReachAlphaIsInconclusive) {
    using cavity::compare::smallestAttainableP;
    EXPECT_DOUBLE_EQ(smallestAttainableP(3, 3), 0.1);
    EXPECT_DOUBLE_EQ(smallestAttainableP(4, 4), 2.0 / 70.0);
    EXPECT_DOUBLE_EQ(smallestAttainableP(3, 5), 2.0 / 56.0);
    EXPECT_DOUBLE_EQ(smallestAttainableP(10, 10), 2.0 / 184756.0);
    cavity::compare::SampleSet a, b;
    for (double v : {1.0, 1.01, 1.02}) a.add(v, "gpu-timestamp");
    for (double v : {2.0, 2.01, 2.02}) b.add(v, "gpu-timestamp");   // twice the time
    const cavity::compare::CompareThresholds t;
    const auto r = cavity::compare::compareSeries("x", "ao", &a, &b, t);
    EXPECT_EQ(r.verdict, "inconclusive");
    EXPECT_EQ(r.reason, "too few samples");
    EXPECT_NE(r.next.find("at least 4"), std::string::npos) << r.next;
    b.add(2.03, "gpu-timestamp");
    a.add(1.03, "gpu-timestamp");
    EXPECT_EQ(cavity::compare::compareSeries("x", "ao", &a, &b, t).verdict, "slower");
}

// On a CPU renderer two runs of one build may take different clocks (the
// check follows the host's load): the verdict is the software renderer's,
// which says so, not "clocks differ".
TEST(CompareVerdict, ASoftwareRenderersClocksApartAreItsOwnVerdict) {
    cavity::compare::SampleSet a, b;
    for (double v : {1.0, 1.01, 1.02, 1.03, 1.04}) {
        a.add(v, "gpu-timestamp");
        b.add(v, "wall");
    }
    const cavity::compare::CompareThresholds t;
    const auto gpu = cavity::compare::compareSeries("x", "ao", &a, &b, t, false);
    EXPECT_EQ(gpu.reason, "clocks differ");
    const auto cpu = cavity::compare::compareSeries("x", "ao", &a, &b, t, true);
    EXPECT_EQ(cpu.verdict, "inconclusive");
    EXPECT_EQ(cpu.reason, "software renderer");
    EXPECT_NE(cpu.next.find("clock each run takes"), std::string::npos) << cpu.next;
}

// The SM clock moved between the runs: the change is judged in cycles (time x
// clock) too, and a verdict stands only where both agree. By hand, in
// thousands of cycles: a at 2000 MHz is 2000, b at 1800 MHz 1980; so b is a
// tenth slower in time and a hundredth fewer in cycles.
TEST(CompareVerdict, AnSmClockDifferenceIsJudgedInCyclesToo) {
    using cavity::compare::compareSeries;
    cavity::compare::SampleSet a, b, c, d;
    for (int i = 0; i < 5; ++i) {
        a.add(1.0, "gpu-timestamp", 2000);
        b.add(1.1, "gpu-timestamp", 1800);
        c.add(1.2, "gpu-timestamp", 1800);
        d.add(1.1, "gpu-timestamp", 1990);   // within one NVML step: not a difference
    }
    const cavity::compare::CompareThresholds t;   // the default --min-change
    const auto clockOnly = compareSeries("x", "ao", &a, &b, t);
    EXPECT_NEAR(clockOnly.changePct, 10.0, 1e-9);
    EXPECT_DOUBLE_EQ(clockOnly.oldSmMhz, 2000);
    EXPECT_DOUBLE_EQ(clockOnly.newSmMhz, 1800);
    EXPECT_NEAR(clockOnly.cyclesChangePct, -1.0, 1e-9);
    EXPECT_EQ(clockOnly.cyclesVerdict, "same");
    EXPECT_EQ(clockOnly.verdict, "inconclusive");
    EXPECT_EQ(clockOnly.reason, "SM clock differs");
    EXPECT_NE(clockOnly.next.find("lock"), std::string::npos);
    // c at 1800 MHz is 2160 thousand cycles: slower in cycles and in time.
    const auto both = compareSeries("x", "ao", &a, &c, t);
    EXPECT_NEAR(both.cyclesChangePct, 8.0, 1e-9);
    EXPECT_EQ(both.cyclesVerdict, "slower");
    EXPECT_EQ(both.verdict, "slower");
    // Within one NVML step the time alone decides, and no cycles are reported.
    const auto oneStep = compareSeries("x", "ao", &a, &d, t);
    EXPECT_EQ(oneStep.verdict, "slower");
    EXPECT_TRUE(oneStep.cyclesVerdict.empty());
    EXPECT_TRUE(std::isnan(oneStep.cyclesChangePct));
    // A side without clocks: time alone, as before.
    cavity::compare::SampleSet e;
    for (int i = 0; i < 5; ++i) e.add(1.1, "gpu-timestamp");
    const auto unknown = compareSeries("x", "ao", &a, &e, t);
    EXPECT_TRUE(std::isnan(unknown.newSmMhz));
    EXPECT_TRUE(unknown.cyclesVerdict.empty());
    EXPECT_EQ(unknown.verdict, "slower");
}

// Both files carry the SM clock (cavity_bench's sm_mhz_median counter,
// results.json's gpu_clocks) and `cavity compare` reports the cycles.
TEST_F(Compare, TheSmClockOfEitherFileReachesTheVerdict) {
    FakeConfig before = fakeConfig(kId, 10, 1, 0), after = fakeConfig(kId, 10, 2, 0.06);   // AO a tenth slower in time
    before.smMhz = 1980;
    // The new clock is lower by as much as the AO pass is slower: the AO pass
    // is the same in cycles, blur and composite take fewer.
    after.smMhz = 1800;
    for (const bool bench : {true, false}) {
        const std::string format = bench ? "bench" : "results";
        const std::string o = write(format + "_old.json", bench ? benchmarkJson({before}) : resultsJson({before}));
        const std::string n = write(format + "_new.json", bench ? benchmarkJson({after}) : resultsJson({after}));
        const std::string out = (dir / "c.json").string();
        const Outcome run = cavity("compare " + o + " " + n + " --json " + out);
        ASSERT_EQ(run.code, 0) << run.output;
        EXPECT_NE(run.output.find("SM MHz old/new"), std::string::npos) << run.output;
        const json rows = rowsOf(out);
        const json& ao = row(rows, kId, "ao");
        EXPECT_EQ(ao["old_sm_mhz"], 1980.0) << format;
        EXPECT_EQ(ao["new_sm_mhz"], 1800.0) << format;
        EXPECT_EQ(ao["cycles_verdict"], "same") << format;
        EXPECT_EQ(ao["verdict"], "inconclusive") << format;
        EXPECT_EQ(ao["reason"], "SM clock differs") << format;
        EXPECT_EQ(row(rows, kId, "blur")["cycles_verdict"], "faster") << format;
        EXPECT_EQ(row(rows, kId, "blur")["verdict"], "inconclusive") << format;
    }
}

// --min-change auto calls a change under the default --min-change when the
// samples can see it; a software renderer's times never give slower or faster.
TEST_F(Compare, AutoThresholdCallsWhatTheNoiseAllowsAndSoftwareRenderersNeverJudge) {
    const auto before = fakeConfig(kId, 20, 1, 0);
    const auto after = fakeConfig(kId, 20, 2, 0.009);   // under --min-change on the AO pass, over its noise
    const std::string o = write("old.json", benchmarkJson({before}));
    const std::string n = write("new.json", benchmarkJson({after}));
    const std::string out = (dir / "v.json").string();
    ASSERT_EQ(cavity("compare " + o + " " + n + " --json " + out).code, 0);
    EXPECT_NE(row(rowsOf(out), kId, "ao")["verdict"], "slower");   // under --min-change
    const Outcome autoRun = cavity("compare " + o + " " + n + " --min-change auto --json " + out);
    ASSERT_EQ(autoRun.code, 0) << autoRun.output;
    const json ao = row(rowsOf(out), kId, "ao");
    EXPECT_EQ(ao["verdict"], "slower") << ao.dump();
    EXPECT_LT(ao["threshold_pct"].get<double>(), 1.5);
    EXPECT_GE(ao["threshold_pct"].get<double>(), cavity::compare::kAutoFloorPct);
    EXPECT_EQ(row(rowsOf(out), kId, "blur")["verdict"], "same");
    // The same numbers from a software renderer: inconclusive, with the reason.
    const std::string os = write("old_sw.json", benchmarkJson({before}, false, true));
    const std::string ns = write("new_sw.json", benchmarkJson({fakeConfig(kId, 20, 2, 0.06)}, false, true));
    const Outcome sw = cavity("compare " + os + " " + ns + " --json " + out + " --fail-on-slower");
    EXPECT_EQ(sw.code, 0) << sw.output;
    const json swAo = row(rowsOf(out), kId, "ao");
    EXPECT_EQ(swAo["verdict"], "inconclusive");
    EXPECT_EQ(swAo["reason"], "software renderer");
    EXPECT_NE(sw.output.find("judge speed on a GPU"), std::string::npos) << sw.output;
}

// Two runs of one build on lavapipe: whatever the host's load did to the
// times, nothing is called slower (or faster).
TEST_F(Compare, IdenticalRunsOnASoftwareRendererAreNeverSlower) {
    const std::string a = (dir / "a").string(), b = (dir / "b").string(), out = (dir / "v.json").string();
    for (const auto& o : {a, b}) {
        const Outcome r = cavity("run --backend vk --res 64x36 --frames 6 --warmup 1 --samples 8,16 --quiet --out " + o);
        ASSERT_EQ(r.code, 0) << r.output;
    }
    const Outcome r = cavity("compare " + a + "/results.json " + b + "/results.json --min-change auto --fail-on-slower --json " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    for (const auto& row : rowsOf(out)) {
        EXPECT_NE(row["verdict"], "slower") << row.dump();
        EXPECT_NE(row["verdict"], "faster") << row.dump();
    }
}

// A filter that matches nothing, or a side flag cavity_bench refuses, is
// bad input found before anything runs or is written.
TEST_F(Compare, AbRefusesASideThatWouldMeasureNothing) {
    const std::string out = (dir / "ab-none").string(), ab = std::string("ab --a ") + CAVITY_BENCH_EXE + " --b " + CAVITY_BENCH_EXE;
    const Outcome none = cavity(ab + " --filter '^nosuch/' --out " + out);
    EXPECT_EQ(none.code, 2) << none.output;
    EXPECT_NE(none.output.find("no benchmark matches --benchmark_filter='^nosuch/'"), std::string::npos) << none.output;
    EXPECT_EQ(std::count(none.output.begin(), none.output.end(), '\n'), 1) << none.output;
    const Outcome bad = cavity(ab + " --filter /alchemy_fast/ --b-args '--frames 0' --out " + out);
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_NE(bad.output.find("--b "), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(out));
}

// cavity ab alternates the two builds (A B, then B A), merges each side's
// rounds into one run of repetitions, and never mixes A's with B's.
TEST_F(Compare, InterleavedRunsAlternateAndKeepTheSidesApart) {
    const std::string out = (dir / "ab").string();
    const Outcome r = cavity(std::string("ab --a ") + CAVITY_BENCH_EXE + " --b " + CAVITY_BENCH_EXE +
                             " --rounds 3 --filter 'corner/alchemy/n16/b4/full/320x180/vk/compute' "
                             "--bench-args='--frames 2 --warmup 0' --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    auto mtime = [&](const std::string& name) { return fs::last_write_time(fs::path(out) / name); };
    EXPECT_LT(mtime("a_0.json"), mtime("b_0.json"));   // round 1: A, B
    EXPECT_LT(mtime("b_1.json"), mtime("a_1.json"));   // round 2: B, A
    EXPECT_LT(mtime("a_2.json"), mtime("b_2.json"));
    for (const char side : {'a', 'b'}) {
        const json merged = cavity::core::readJsonFile(out + "/" + side + ".json").value();
        std::vector<double> times, expected;
        for (const auto& e : merged["benchmarks"])
            if (e["run_name"].get<std::string>().find('@') == std::string::npos) {
                EXPECT_EQ(e["repetition_index"], int(times.size()));
                times.push_back(e["real_time"]);
            }
        for (int k = 0; k < 3; ++k) {
            const json round = cavity::core::readJsonFile(out + "/" + side + "_" + std::to_string(k) + ".json").value();
            for (const auto& e : round["benchmarks"])
                if (e["run_type"] == "iteration" && e["run_name"].get<std::string>().find('@') == std::string::npos)
                    expected.push_back(e["real_time"]);
        }
        EXPECT_EQ(times, expected) << side;
    }
    const json rows = rowsOf(out + "/compare.json");
    ASSERT_FALSE(rows.empty());
    for (const auto& row : rows) {
        EXPECT_EQ(row["n_old"], 3) << row.dump();
        EXPECT_EQ(row["n_new"], 3) << row.dump();
    }
}

// One build against itself with two edited kernels on B's side only
// (--b-args '--kernel-source ... --kernel-source ...'): B's processes measure
// both edits and record them, A's do not, and each edit's cost shows in the
// pass that runs it. (On a
// software renderer compare calls no pass slower or faster, so the medians
// are read here.)
TEST_F(Compare, AnEditedKernelOnOneSideIsMeasuredInItsPass) {
    fs::create_directories(dir);
    const fs::path slow = dir / "slow.glsl";
    std::ofstream(slow) << "#include \"include/common.glsl\"\n"
                           "void cavity_main(ivec2 pixel) {\n"
                           "    float x = texelFetch(in_zmip, pixel, 0).r;\n"
                           "    for (int i = 0; i < 4000; ++i) x = fma(x, 0.9999, 1e-4);\n"
                           "    write_ao(pixel, vec4(min(x, 1.0)));\n"
                           "    write_ao_key(pixel, vec4(1.0, texelFetch(in_zmip, pixel, 0).r, 0.0, 0.0));\n}\n";
    // A second edit, given with the flag once more: the composite with the
    // same loop before its own body.
    std::ifstream stock(std::string(CAVITY_SOURCE_DIR) + "/kernels/passes/composite/composite.glsl");
    std::string composite((std::istreambuf_iterator<char>(stock)), std::istreambuf_iterator<char>());
    const std::string entry = "void cavity_main(ivec2 pixel) {\n";
    const size_t at = composite.find(entry);
    ASSERT_NE(at, std::string::npos);
    composite.insert(at + entry.size(), "    float y = float(pixel.x);\n"
                                        "    for (int i = 0; i < 4000; ++i) y = fma(y, 0.9999, 1e-4);\n"
                                        "    if (y < -1.0) return;\n");
    const fs::path slowComposite = dir / "slow_composite.glsl";
    std::ofstream(slowComposite) << composite;
    const std::string out = (dir / "ab").string();
    const Outcome r = cavity(std::string("ab --a ") + CAVITY_BENCH_EXE + " --b " + CAVITY_BENCH_EXE +
                             " --rounds 4 --filter 'corner/alchemy_fast/n16/b4/full/320x180/vk/compute' "
                             "--bench-args='--frames 2 --warmup 0' --b-args '--kernel-source ssao_alchemy_fast.glsl=" +
                             slow.string() + " --kernel-source composite.glsl=" + slowComposite.string() + "' --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const json a = cavity::core::readJsonFile(out + "/a_0.json").value(), b = cavity::core::readJsonFile(out + "/b_0.json").value();
    EXPECT_FALSE(a["context"].contains("cavity_kernel_sources"));
    EXPECT_NE(b["context"].value("cavity_kernel_sources", "").find("ssao_alchemy_fast.glsl=" + slow.string()), std::string::npos);
    EXPECT_NE(b["context"].value("cavity_kernel_sources", "").find("composite.glsl=" + slowComposite.string()),
              std::string::npos);
    auto passTimes = [&](const char* side, const std::string& pass) {
        std::vector<double> t;
        const json merged = cavity::core::readJsonFile(out + "/" + side + ".json").value();
        for (const auto& e : merged["benchmarks"])
            if (e["run_name"].get<std::string>().find('@') == std::string::npos) t.push_back(e["pass_" + pass + "_ms"]);
        std::sort(t.begin(), t.end());
        return t;
    };
    const auto aoA = passTimes("a", "ao"), aoB = passTimes("b", "ao");
    ASSERT_EQ(aoA.size(), 4u);
    ASSERT_EQ(aoB.size(), 4u);
    // Medians of the 4 rounds: a software renderer under a loaded CI host
    // can stretch any single round (one of A's read 3x its others).
    auto median = [](const std::vector<double>& t) { return (t[1] + t[2]) / 2; };
    EXPECT_GT(median(aoB), 2 * median(aoA));   // 4000 FMAs a pixel against 16 samples
    const auto compositeA = passTimes("a", "composite"), compositeB = passTimes("b", "composite");
    EXPECT_GT(median(compositeB), 2 * median(compositeA));
    const auto blurA = passTimes("a", "blur_x"), blurB = passTimes("b", "blur_x");
    EXPECT_LT(blurB[1], 2 * blurA[2]);          // the passes it does not touch
    EXPECT_LT(blurA[1], 2 * blurB[2]);
}

TEST_F(Compare, ResultsJsonAgainstResultsJsonAndAgainstBenchmarkJson) {
    const auto before = fakeConfig(kId, 40, 3, 0);
    const auto after = fakeConfig(kId, 40, 4, 0.03);
    fs::create_directories(dir / "old");
    const std::string oldResults = write("old/results.json", resultsJson({before}));
    const std::string newResults = write("new_results.json", resultsJson({after}));
    const std::string out = (dir / "v.json").string();
    Outcome r = cavity("compare " + oldResults + " " + newResults + " --json " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    json rows = rowsOf(out);
    EXPECT_EQ(row(rows, kId, "ao")["verdict"], "slower");
    EXPECT_EQ(row(rows, kId, "ao")["n_old"], 40);
    EXPECT_EQ(row(rows, kId, "gbuffer")["verdict"], "same");   // every frame 0.05 on both sides
    EXPECT_EQ(row(rows, kId, "frame")["verdict"], "slower");
    EXPECT_LE(row(rows, kId, "ao")["ci_low_ms"].get<double>(), 0.03);
    EXPECT_GE(row(rows, kId, "ao")["ci_high_ms"].get<double>(), 0.03);

    // Frames against repetitions, matched by id and pass: the passes pair up,
    // the frame (results.json) and the pipeline (benchmark) do not.
    const std::string bench = write("bench.json", benchmarkJson({fakeConfig(kId, 8, 5, 0.03)}));
    r = cavity("compare " + oldResults + " " + bench + " --json " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    rows = rowsOf(out);
    EXPECT_EQ(row(rows, kId, "ao")["verdict"], "slower");
    EXPECT_EQ(row(rows, kId, "ao")["n_new"], 8);
    EXPECT_EQ(row(rows, kId, "ao")["method"], "exact");   // 8 repetitions, no ties
    EXPECT_EQ(row(rows, kId, "blur")["verdict"], "same");
    EXPECT_EQ(row(rows, kId, "frame")["verdict"], "gone");
    EXPECT_EQ(row(rows, kId, "gbuffer")["verdict"], "gone");
    EXPECT_EQ(row(rows, kId, "pipeline")["verdict"], "new");
}

TEST_F(Compare, ClocksAreNeverPooled) {
    // The new run's second configuration fell back to the wall clock for some
    // repetitions; a third configuration is on the wall clock in the new run only;
    // a fourth has two repetitions.
    auto mixed = fakeConfig(kOtherId, 10, 6, 0.1);
    for (size_t i = 0; i < mixed.clocks.size(); i += 2) mixed.clocks[i] = "wall";
    const std::string third = "open/alchemy/n16/b4/full/1920x1080/vk/compute";
    const std::string fourth = "grille/alchemy/n16/b4/full/1920x1080/vk/compute";
    const std::string o = write("old.json", benchmarkJson({fakeConfig(kId, 10, 1, 0), fakeConfig(kOtherId, 10, 2, 0),
                                                           fakeConfig(third, 10, 3, 0), fakeConfig(fourth, 2, 4, 0)}));
    const std::string n = write("new.json", benchmarkJson({fakeConfig(kId, 10, 5, 0), mixed,
                                                           fakeConfig(third, 10, 7, 0.1, "wall"),
                                                           fakeConfig(fourth, 2, 8, 0.3)}));
    const std::string out = (dir / "v.json").string();
    const Outcome r = cavity("compare " + o + " " + n + " --json " + out + " --fail-on-slower");
    EXPECT_EQ(r.code, 0) << r.output;   // no verdict, so nothing slower
    const json rows = rowsOf(out);
    for (const char* pass : {"pipeline", "ao", "blur", "composite"}) {
        const json& m = row(rows, kOtherId, pass);
        EXPECT_EQ(m["verdict"], "inconclusive") << pass;
        EXPECT_EQ(m["reason"], "mixed clocks") << pass;
        EXPECT_NE(m["next"].get<std::string>().find("one clock"), std::string::npos) << pass;
        EXPECT_EQ(m["new_clock"], "mixed");
        EXPECT_TRUE(m["p"].is_null());
        EXPECT_TRUE(m["change_pct"].is_null());
        EXPECT_TRUE(m["new_median_ms"].is_null());
        const json& d = row(rows, third, pass);
        EXPECT_EQ(d["verdict"], "inconclusive") << pass;
        EXPECT_EQ(d["reason"], "clocks differ") << pass;
        EXPECT_EQ(d["old_clock"], "gpu-timestamp");
        EXPECT_EQ(d["new_clock"], "wall");
        EXPECT_TRUE(d["p"].is_null());
        EXPECT_EQ(row(rows, fourth, pass)["verdict"], "inconclusive") << pass;
        EXPECT_EQ(row(rows, fourth, pass)["reason"], "too few samples") << pass;
        EXPECT_EQ(row(rows, kId, pass)["verdict"], "same") << pass;
    }
    EXPECT_NE(r.output.find("mixed clocks"), std::string::npos);
}

// One repetition in ten on the wall clock (its warm clock check failed)
// leaves it out and judges the other nine; three in ten (more than a
// quarter) leave the configuration without a verdict.
TEST_F(Compare, AFewSamplesOnAnotherClockAreLeftOut) {
    auto oneOff = fakeConfig(kOtherId, 10, 6, 0.1);
    oneOff.clocks[3] = "wall";
    auto threeOff = fakeConfig(kId, 10, 5, 0.1);
    for (size_t i : {1, 4, 7}) threeOff.clocks[i] = "wall";
    const std::string o = write("old.json", benchmarkJson({fakeConfig(kId, 10, 1, 0), fakeConfig(kOtherId, 10, 2, 0)}));
    const std::string n = write("new.json", benchmarkJson({threeOff, oneOff}));
    const std::string out = (dir / "v.json").string();
    const Outcome r = cavity("compare " + o + " " + n + " --json " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    const json rows = rowsOf(out);
    for (const char* pass : {"pipeline", "ao", "blur", "composite"}) {
        const json& one = row(rows, kOtherId, pass);
        const bool shifted = std::string(pass) == "ao" || std::string(pass) == "pipeline";   // the AO pass shifted
        EXPECT_EQ(one["verdict"], shifted ? "slower" : "same") << pass;
        EXPECT_EQ(one["n_new"], 9) << pass;
        EXPECT_EQ(one["left_out_new"], 1) << pass;
        EXPECT_EQ(one["left_out_old"], 0) << pass;
        EXPECT_EQ(one["new_clock"], "gpu-timestamp") << pass;
        const json& three = row(rows, kId, pass);
        EXPECT_EQ(three["verdict"], "inconclusive") << pass;
        EXPECT_EQ(three["reason"], "mixed clocks") << pass;
    }
    EXPECT_NE(r.output.find("4 rows judged on the clock most of their samples share, 4 samples on another clock left out"),
              std::string::npos)
        << r.output;
}

// ---- bad input ----

TEST_F(Compare, BadInputExitsTwoWithOneLineNamingIt) {
    const std::string good = write("good.json", benchmarkJson({fakeConfig(kId, 5, 1, 0)}));
    // Two files (one file as both runs is refused): the flag errors below come first.
    const std::string good2 = write("good2.json", benchmarkJson({fakeConfig(kId, 5, 1, 0)}));
    const std::string garbage = write("garbage.json", "{\n  \"benchmarks\": [\n    {\"name\": oops}\n  ]\n}\n");
    const std::string neither = write("neither.json", R"({"schema": "cavity.gate/1", "rows": []})");
    const std::string badUnit = write("unit.json", R"({"benchmarks": [{"name": "a/b", "run_type": "iteration",
                                                   "real_time": 1, "time_unit": "min"}]})");
    fs::create_directories(dir / "folder.json");
    const std::string folder = (dir / "folder.json").string(), missing = (dir / "missing.json").string();
    const std::string out = (dir / "v.json").string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {missing + " " + good, "cavity compare: " + missing + ": cannot be read (no such file)"},
        {good + " " + folder, "cavity compare: " + folder + ": is a folder, not a JSON file"},
        {good + " " + garbage, "cavity compare: " + garbage + ": does not parse: line 3: syntax error"},
        {neither + " " + good, "cavity compare: " + neither +
                                   ": neither a cavity results.json (schema cavity.results/1) nor Google Benchmark "
                                   "JSON (benchmarks[])"},
        {good + " " + badUnit, "cavity compare: " + badUnit + ": benchmarks[0] a/b: time_unit \"min\": must be ns, us, ms or s"},
        {good, "cavity compare: need two files, OLD.json NEW.json (have 1; see cavity compare --help)"},
        {good + " " + good2 + " --alpha 1.5", "cavity compare: --alpha '1.5': must be a number in (0, 1)"},
        {good + " " + good2 + " --alpha", "cavity compare: --alpha: missing value"},
        {good + " " + good2 + " --min-change -1", "cavity compare: --min-change '-1': must be a percentage >= 0"},
        {good + " " + good2 + " --json", "cavity compare: --json: missing value"},
        {good + " " + good2 + " --bogus", "cavity compare: --bogus: unknown flag (see cavity compare --help)"},
        {good + " " + good2 + " --json " + (dir / "no" / "such" / "v.json").string(),
         "cavity compare: --json " + (dir / "no" / "such" / "v.json").string() + ": cannot write"},
        // Onto a folder: exit 2 and nothing left behind (was exit 4 and a .tmp-<pid>).
        {good + " " + good2 + " --json " + folder, "cavity compare: --json " + folder + ": is a folder"},
        {good + " " + good2 + " --filter zzz", "cavity compare: --filter: matches no"},
        {good + " " + good2 + " --filter '('", "cavity compare: --filter"},
    };
    for (const auto& [args, message] : cases) {
        const Outcome o = cavity("compare " + args + (args.find("--json") == std::string::npos ? " --json " + out : ""));
        EXPECT_EQ(o.code, 2) << args << "\n" << o.output;
        EXPECT_EQ(o.output.rfind(message, 0), 0u) << args << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << args << "\n" << o.output;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
    for (const auto& e : fs::recursive_directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

}  // namespace
