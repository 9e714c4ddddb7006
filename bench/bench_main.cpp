// The benchmark runner: one Google Benchmark per configuration of the sweep
// (harness/sweep.h), named by its configuration id. Each benchmark iteration
// is one whole measurement (harness/timing.h): frames recorded back to back
// after a steady warm-up until the medians are known to 0.5%; the iteration's
// time is the median per-frame GPU time of the AO pipeline (every pass but
// the G-buffer), from the backend's timestamps (UseManualTime) or from the
// drained wall clock where the timestamps do not bracket the work. Run with
// --benchmark_repetitions=N (and --benchmark_enable_random_interleaving) for
// N independent measurements.
//
//   cavity_bench [--backend gl|vk|all] [--sweep gpu|cpu|auto] [--frames N] [--warmup N]
//                [--timing batch|drained] [--max-noise PCT] [--max-time S]
//                [--plant PASS:FMAS[,PASS:FMAS]] [--plant-file FILE.json] [--device K]
//                [google benchmark flags: --benchmark_filter=..., --benchmark_out=..., ...]
#include "bench_runner.h"
#include "per_pass_reporter.h"

#include "cli.h"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>

namespace {

constexpr const char* kUsage =
    "usage: cavity_bench [--backend gl|vk|all] [--sweep gpu|cpu|auto] [--frames N] [--warmup N]\n"
    "                    [--timing batch|drained] [--max-noise PCT] [--max-time S]\n"
    "                    [--plant PASS:FMAS[,PASS:FMAS..]] [--plant-file FILE.json] [--device K]\n"
    "                    [--benchmark_* flags]\n";

using cavity::Result;
using cavity::Status;

Status parsePlant(const std::string& text, cavity::PlantedSlowdown& plant) {
    CAVITY_ASSIGN(const auto items, cavity::cli::splitList("--plant", text));
    for (const auto& item : items) {
        const auto colon = item.find(':');
        if (colon == std::string::npos || colon == 0)
            return cavity::badInput("--plant '" + item + "': must be PASS:FMAS, e.g. ao:120");
        CAVITY_ASSIGN(const int n, cavity::cli::parseInt("--plant " + item.substr(0, colon), item.substr(colon + 1), 1,
                                                         1000000));
        if (!plant.emplace(item.substr(0, colon), n).second)
            return cavity::badInput("--plant " + item.substr(0, colon) + ": given twice");
    }
    return {};
}

// {"<configuration id>": {"<pass>": FMAS, ...}, ...} (scripts/plant_calibrate.py writes it).
Status readPlantFile(const std::string& path, std::map<std::string, cavity::PlantedSlowdown>& out) {
    std::ifstream f(path);
    if (!f || std::filesystem::is_directory(path)) return cavity::badInput("--plant-file " + path + ": cannot be read");
    try {
        const auto doc = nlohmann::json::parse(f);
        for (const auto& [id, passes] : doc.items())
            for (const auto& [pass, n] : passes.items()) {
                if (!n.is_number_integer() || n.get<long>() < 1 || n.get<long>() > 1000000)
                    return cavity::badInput("--plant-file " + path + ": " + id + " " + pass + " = " + n.dump() +
                                            ": must be an integer in 1..1000000");
                out[id][pass] = n.get<int>();
            }
    } catch (const nlohmann::json::exception& e) {
        return cavity::badInput("--plant-file " + path + ": " + e.what());
    }
    return {};
}

// Takes Cavity's own flags out of argv; the rest goes to Google Benchmark.
Result<cavity::bench::Options> parse(int argc, char** argv, std::vector<char*>& rest) {
    using namespace cavity::cli;
    cavity::bench::Options o;
    rest = {argv[0]};
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") return cavity::badInput(kUsage);
        if (arg.rfind("--benchmark_", 0) == 0 || arg.rfind("--v=", 0) == 0 || arg.rfind("--", 0) != 0) {
            rest.push_back(argv[i]);
            continue;
        }
        std::string flag = arg, value;
        if (const auto eq = arg.find('='); eq != std::string::npos) {
            flag = arg.substr(0, eq);
            value = arg.substr(eq + 1);
        } else if (i + 1 < argc) {
            value = argv[++i];
        } else {
            return cavity::badInput(flag + ": missing value");
        }
        if (flag == "--backend") {
            if (value != "gl" && value != "vk" && value != "all")
                return cavity::badInput("--backend '" + value + "': must be gl, vk or all");
            o.backend = value;
        } else if (flag == "--sweep") {
            if (value != "gpu" && value != "cpu" && value != "auto")
                return cavity::badInput("--sweep '" + value + "': must be gpu, cpu or auto");
            o.sweep = value;
        } else if (flag == "--frames" || flag == "--iterations") {
            CAVITY_ASSIGN(o.frames, parseInt(flag, value, 1, 1000000));
        } else if (flag == "--warmup") {
            CAVITY_ASSIGN(o.warmup, parseInt(flag, value, 0, 100000));
        } else if (flag == "--timing") {
            if (value != "batch" && value != "drained")
                return cavity::badInput("--timing '" + value + "': must be batch or drained");
            o.mode = value == "batch" ? cavity::TimingMode::Batch : cavity::TimingMode::Drained;
        } else if (flag == "--max-noise") {
            CAVITY_ASSIGN(const double pct, parseNumber(flag, value, 0, 100));
            o.maxNoise = pct / 100;
        } else if (flag == "--max-time") {
            CAVITY_ASSIGN(o.maxSeconds, parseNumber(flag, value, 0.001, 3600));
        } else if (flag == "--plant") {
            CAVITY_TRY(parsePlant(value, o.plant));
        } else if (flag == "--plant-file") {
            CAVITY_TRY(readPlantFile(value, o.plantById));
        } else if (flag == "--device") {
            CAVITY_ASSIGN(o.device, parseInt(flag, value, 0, 64));
        } else {
            const std::string near = cavity::cli::nearest(
                flag, {"--backend", "--sweep", "--frames", "--iterations", "--warmup", "--timing", "--max-noise",
                       "--max-time", "--plant", "--plant-file", "--device"});
            return cavity::badInput(flag + ": unknown flag (" + (near.empty() ? "" : "did you mean " + near + "? ") +
                                    "see cavity_bench --help)");
        }
    }
    return o;
}

// The value of a Google Benchmark flag as given (--name=value), or empty.
std::string benchmarkFlag(const std::vector<char*>& args, const char* name) {
    const std::string prefix = std::string("--") + name + "=";
    std::string v;
    for (const char* a : args)
        if (std::strncmp(a, prefix.c_str(), prefix.size()) == 0) v = a + prefix.size();
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<char*> rest;
    auto options = parse(argc, argv, rest);
    if (!options) {
        const bool help = options.error().message == kUsage;
        (help ? std::cout : std::cerr) << (help ? "" : "cavity_bench: ") << options.error().message
                                       << (help ? "" : "\n");
        return help ? 0 : 2;
    }
    // Read before Initialize, which takes its flags out of the list.
    const std::string out = benchmarkFlag(rest, "benchmark_out"), format = benchmarkFlag(rest, "benchmark_out_format"),
                      filter = benchmarkFlag(rest, "benchmark_filter");
    // Google Benchmark compiles the filter as a std::regex (extended; '-'
    // first negates it) and prints its own error before running nothing; ours
    // is one line and exit 2.
    if (!filter.empty()) {
        try {
            std::regex(filter[0] == '-' ? filter.substr(1) : filter, std::regex_constants::extended);
        } catch (const std::regex_error& e) {
            std::cerr << "cavity_bench: --benchmark_filter='" << filter << "': not a regular expression (" << e.what() << ")\n";
            return 2;
        }
    }
    int n = int(rest.size());
    benchmark::Initialize(&n, rest.data());
    if (benchmark::ReportUnrecognizedArguments(n, rest.data())) return 2;
    auto registered = cavity::bench::registerSweep(*options);
    if (!registered) {
        std::cerr << "cavity_bench: " << registered.error().message << "\n";
        return static_cast<int>(registered.error().code);
    }
    // A JSON file gets one more entry per pass (<id>@<pass>), so that Google
    // Benchmark's compare.py, which judges only a benchmark's time, sees
    // every pass as well (bench/per_pass_reporter.h).
    std::unique_ptr<benchmark::BenchmarkReporter> file;
    if (!out.empty() && (format.empty() || format == "json"))
        file = std::make_unique<cavity::bench::PerPassJsonReporter>();
    const size_t ran = benchmark::RunSpecifiedBenchmarks(nullptr, file.get());
    benchmark::Shutdown();
    cavity::bench::releaseBackends();
    if (ran == 0) {
        std::cerr << "cavity_bench: no benchmark matches --benchmark_filter='" << filter << "'\n";
        return 2;
    }
    return 0;
}
