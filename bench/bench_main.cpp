// The benchmark runner: one Google Benchmark per configuration of the sweep
// (harness/plan/sweep.h), named by its configuration id. Each benchmark iteration
// is one whole measurement (harness/measure/timing.h): frames recorded back to back
// after a steady warm-up until the medians meet the noise target; the iteration's
// time is the median per-frame GPU time of the AO pipeline (every pass but
// the G-buffer), from the backend's timestamps (UseManualTime) or from the
// drained wall clock where the timestamps do not bracket the work. Run with
// --benchmark_repetitions=N (and --benchmark_enable_random_interleaving) for
// N independent measurements.
//
// Its own flags are declared once (benchSpec below) and parsed by CLI11
// through cli/flags.h, as cavity's are; --benchmark_* and --v= go to
// Google Benchmark untouched.
#include "core/json_file.h"
#include "core/regex_guard.h"
#include "bench_runner.h"
#include "package/package.h"
#include "console_reporter.h"
#include "per_pass_reporter.h"

#include "values.h"
#include "flags.h"
#include "version.h"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>
#include <iostream>
#include <memory>
#include <regex>
#include <set>

namespace {

using cavity::Result;
using cavity::Status;

Status parsePlant(const std::string& text, cavity::pipeline::PlantedSlowdown& plant) {
    CAVITY_ASSIGN(const auto items, cavity::flags::splitList("--plant", text));
    for (const auto& item : items) {
        const auto colon = item.find(':');
        if (colon == std::string::npos || colon == 0)
            return cavity::badInput("--plant '" + item + "': must be PASS:FMAS, e.g. ao:120");
        CAVITY_ASSIGN(const int n, cavity::flags::parseInt("--plant " + item.substr(0, colon), item.substr(colon + 1), 1,
                                                         1000000));
        if (!plant.emplace(item.substr(0, colon), n).second)
            return cavity::badInput("--plant " + item.substr(0, colon) + ": given twice");
    }
    return {};
}

// {"<configuration id>": {"<pass>": FMAS, ...}, ...} (scripts/plant_calibrate.py writes it).
Status readPlantFile(const std::string& path, std::map<std::string, cavity::pipeline::PlantedSlowdown>& out) {
    std::ifstream f(path);
    if (!f || std::filesystem::is_directory(path)) return cavity::badInput("--plant-file " + path + ": cannot be read");
    try {
        const auto doc = nlohmann::json::parse(f);
        if (!doc.is_object() || doc.empty())
            return cavity::badInput("--plant-file " + path + ": must be a non-empty object {\"<id>\": {\"<pass>\": FMAS}}, not " +
                                    std::string(doc.type_name()) + (doc.empty() ? " (empty)" : ""));
        for (const auto& [id, passes] : doc.items()) {
            if (!passes.is_object() || passes.empty())
                return cavity::badInput("--plant-file " + path + ": " + id + ": must be a non-empty object {\"<pass>\": FMAS}");
            for (const auto& [pass, n] : passes.items()) {
                if (!n.is_number_integer() || n.get<long>() < 1 || n.get<long>() > 1000000)
                    return cavity::badInput("--plant-file " + path + ": " + id + " " + pass + " = " + cavity::core::jsonText(n) +
                                            ": must be an integer in 1..1000000");
                out[id][pass] = n.get<int>();
            }
        }
    } catch (const nlohmann::json::exception& e) {
        return cavity::badInput("--plant-file " + path + ": " + e.what());
    }
    return {};
}

// The flags of cavity_bench, declared once: --help and the parse read this.
const cavity::flags::CommandSpec& benchSpec() {
    static const cavity::flags::CommandSpec spec = [] {
        cavity::flags::CommandSpec c;
        c.program = "cavity_bench";
        c.description =
            "One Google Benchmark per configuration of the sweep (harness/plan/sweep.h), named by its configuration id; "
            "each iteration is one whole measurement, its time the median per-frame GPU time of the AO pipeline. "
            "Google Benchmark's own flags (--benchmark_filter=REGEX, --benchmark_out=FILE, "
            "--benchmark_repetitions=N, --benchmark_list_tests and the rest) are passed to it; give them as --name=value.";
        c.flags = {
            {"--backend", "gl|vk|all", "backends to measure (default all)"},
            {"--sweep", "gpu|cpu|auto", "the configurations: the GPU sweep, the smaller CPU-renderer one, or by device (default auto)"},
            {"--frames", "N", "measured frames, at least (1..1000000)"},
            {"--iterations", "N", "the same as --frames"},
            {"--warmup", "N", "warm-up frames, at least (0..100000)"},
            {"--timing", "batch|drained", "batch: back-to-back frames; drained: wait for the GPU after each (default: the device's)"},
            {"--max-noise", "PCT", "stop measuring once the median's noise is under PCT percent (0..100)"},
            {"--max-time", "S", "stop measuring after S seconds (0.001..3600)"},
            {"--plant", "PASS:FMAS[,..]", "plant FMAS dependent FMAs per pixel in PASS (1..1000000; the timing-verdict check)"},
            {"--plant-file", "FILE.json", "planted FMAs per configuration id and pass ({\"<id>\": {\"<pass>\": FMAS}})"},
            {"--kernel-source", "NAME=FILE", "measure with kernels/NAME replaced by FILE's text (an edited kernel); repeatable",
             "Options", true},
            {"--device", "K", "device index (0..64; default 0)"},
        };
        c.footer = "\n" + cavity::flags::kernelHelp("Kernels (the sweep's AO pipelines; select by id with --benchmark_filter)") +
                   "\nExit codes: 0 every benchmark measured, 2 bad usage (or no benchmark matches the filter, or a benchmark "
                   "failed on what was given: a kernel source that does not compile), 3 no backend, 4 GPU error.";
        c.examples = {
            "cavity_bench --backend vk --benchmark_filter=/alchemy_fast/",
            "cavity_bench --sweep cpu --benchmark_repetitions=5 --benchmark_out=out/bench.json",
            "cavity_bench --benchmark_list_tests",
        };
        return c;
    }();
    return spec;
}

// Takes Cavity's own flags out of argv; --benchmark_* and --v= go to Google Benchmark.
Result<cavity::bench::Options> parse(int argc, char** argv, std::vector<char*>& rest, bool& help) {
    using cavity::flags::addKernelSource;
    using cavity::flags::helpText;
    using cavity::flags::ParsedFlags;
    using cavity::flags::parseFlags;
    using cavity::flags::parseInt;
    using cavity::flags::parseNumber;
    cavity::bench::Options o;
    rest = {argv[0]};
    std::vector<std::string> own;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--benchmark_", 0) == 0 || arg.rfind("--v=", 0) == 0) rest.push_back(argv[i]);
        else own.push_back(arg);
    }
    CAVITY_ASSIGN(const ParsedFlags parsed, parseFlags(benchSpec(), own));
    help = parsed.help;
    if (help) {
        std::cout << parsed.helpText;
        return o;
    }
    for (const auto& [flag, value] : parsed.values) {
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
            o.mode = value == "batch" ? cavity::measure::TimingMode::Batch : cavity::measure::TimingMode::Drained;
        } else if (flag == "--max-noise") {
            CAVITY_ASSIGN(const double pct, parseNumber(flag, value, 0, 100));
            o.maxNoise = pct / 100;
        } else if (flag == "--max-time") {
            CAVITY_ASSIGN(o.maxSeconds, parseNumber(flag, value, 0.001, 3600));
        } else if (flag == "--plant") {
            CAVITY_TRY(parsePlant(value, o.plant));
        } else if (flag == "--plant-file") {
            CAVITY_TRY(readPlantFile(value, o.plantById));
        } else if (flag == "--kernel-source") {
            CAVITY_TRY(addKernelSource(value, o.overrides, o.replaced));
        } else if (flag == "--device") {
            CAVITY_ASSIGN(o.device, parseInt(flag, value, 0, 64));
        }
    }
    const auto given = [&](const char* name) {
        return std::any_of(parsed.values.begin(), parsed.values.end(), [&](const auto& v) { return v.first == name; });
    };
    if (given("--plant") && given("--plant-file"))
        return cavity::badInput("--plant and --plant-file: give one (the file plants per configuration, --plant everywhere)");
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

// What Google Benchmark would find late or say in its own words: the
// filter, compiled as a std::regex (extended; '-' first negates it), and an
// unwritable --benchmark_out, found only after the whole sweep has run.
cavity::Status checkBenchmarkFlags(const std::vector<char*>& args, const std::string& filter, const std::string& out) {
    const auto given = [&](const char* name) {
        const std::string prefix = std::string("--") + name + "=";
        return std::any_of(args.begin(), args.end(), [&](const char* a) { return std::strncmp(a, prefix.c_str(), prefix.size()) == 0; });
    };
    // Given twice, Google Benchmark takes the last: a wrapper's flag (cavity
    // ab's --benchmark_out) would be overridden without a word.
    std::set<std::string> seen;
    for (const char* a : args) {
        const std::string arg = a, name = arg.substr(0, arg.find('='));
        if (!seen.insert(name).second) return cavity::badInput(name + ": given twice");
    }
    if (given("benchmark_filter") && filter.empty())
        return cavity::badInput("--benchmark_filter='': empty; give a regular expression (or leave the flag out for every benchmark)");
    if (cavity::core::longestAlternative(filter) > cavity::core::kMaxPatternLength)
        return cavity::badInput(cavity::core::nestedQuantifierError("--benchmark_filter", filter));
    // Google Benchmark compiles it with std::regex and, where that fails (an
    // alternation past std::regex's state limit), prints its own lines and
    // runs nothing: one line here instead. A leading '-' negates the rest.
    if (!filter.empty()) {
        try {
            const std::regex compiled(filter[0] == '-' ? filter.substr(1) : filter);
        } catch (const std::regex_error& e) {
            std::string why = "--benchmark_filter '";
            why += filter.substr(0, 40);
            why += "...' (" + std::to_string(filter.size()) + " characters): not a regular expression std::regex takes (";
            why += e.what();
            return cavity::badInput(why + ")");
        }
    }
    // A minimum time is seconds above 0 (Google Benchmark 1.7 reads a bare
    // number, and ran a negative or unreadable one as its default).
    for (const char* name : {"benchmark_min_time", "benchmark_min_warmup_time"})
        if (given(name)) {
            const std::string v = benchmarkFlag(args, name);
            static const std::regex form("[0-9]*\\.?[0-9]+(e[+-]?[0-9]+)?");
            if (!std::regex_match(v, form) || std::strtod(v.c_str(), nullptr) <= 0)
                return cavity::badInput(std::string("--") + name + "='" + v + "': must be a number of seconds above 0");
        }
    // Google Benchmark takes a repetition count below 1 as a vector size
    // (and throws), and 0 as a run that measured nothing.
    if (given("benchmark_repetitions"))
        if (auto r = cavity::flags::parseInt("--benchmark_repetitions", benchmarkFlag(args, "benchmark_repetitions"), 1, 10000); !r)
            return r.error();
    for (const char* name : {"benchmark_out_format", "benchmark_format"}) {
        const std::string v = benchmarkFlag(args, name);
        if (given(name) && v != "json" && v != "console" && v != "csv")
            return cavity::badInput(std::string("--") + name + "='" + v + "': must be json, console or csv");
    }
    if (!filter.empty()) {
        try {
            std::regex(filter[0] == '-' ? filter.substr(1) : filter, std::regex_constants::extended);
        } catch (const std::regex_error& e) {
            return cavity::badInput("--benchmark_filter='" + filter + "': not a regular expression (" + e.what() + ")");
        }
    }
    if (!out.empty()) {
        namespace fs = std::filesystem;
        std::error_code ec;
        const fs::path parent = fs::path(out).has_parent_path() ? fs::path(out).parent_path() : fs::path(".");
        const char* why = fs::is_directory(out, ec)        ? "is a folder"
                          : !fs::is_directory(parent, ec)  ? "its folder does not exist"
                          : ::access(parent.c_str(), W_OK) ? "its folder is not writable"
                                                           : nullptr;
        if (why) return cavity::badInput("--benchmark_out=" + out + ": cannot be written (" + why + ")");
    }
    return {};
}

// The exit code of a run of `ran` benchmarks: none run is a filter that
// matched nothing; one that failed gives its code, so that a run that
// measured nothing, or part of what it was asked, never exits 0.
int runExitCode(size_t ran, const std::string& filter) {
    if (ran == 0) {
        std::cerr << "cavity_bench: no benchmark matches --benchmark_filter='" << filter << "'\n";
        return 2;
    }
    if (const auto& failed = cavity::bench::failures(); !failed.empty()) {
        // 2 for what the user gave (a kernel source that does not compile, a
        // bad CAVITY_WORKGROUP), 3 or 4 for the backend.
        std::cerr << "cavity_bench: " << failed.size() << " of " << ran << " benchmarks measured nothing; first, "
                  << failed[0].id << ": " << failed[0].error.message << "\n";
        return static_cast<int>(failed[0].error.code);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Kernel packages first (--kernels DIR, CAVITY_KERNELS): the sweep and the
    // flags then hold their kernels and parameters.
    if (const auto loaded = cavity::kernels::loadPackagesFromCommandLine(argc, argv); !loaded) {
        std::cerr << "cavity_bench: " << cavity::flags::printable(loaded.error().message) << "\n";
        return 2;
    }
    if (argc > 1 && std::string(argv[1]) == "--version") {
        std::cout << cavity::flags::versionLine("cavity_bench") << "\n";
        return 0;
    }
    std::vector<char*> rest;
    bool help = false;
    auto options = parse(argc, argv, rest, help);
    if (!options) {
        std::cerr << "cavity_bench: " << cavity::flags::printable(options.error().message) << "\n";
        return 2;
    }
    if (help) return 0;
    // Listing runs nothing, yet Google Benchmark would still open
    // --benchmark_out and leave the file empty: a listing never touches it.
    const std::string list = benchmarkFlag(rest, "benchmark_list_tests");
    const bool listing = list == "true" || list == "1" ||
                         std::any_of(rest.begin(), rest.end(), [](const char* a) { return std::strcmp(a, "--benchmark_list_tests") == 0; });
    if (listing)
        std::erase_if(rest, [](const char* a) { return std::strncmp(a, "--benchmark_out=", 16) == 0; });
    // Read before Initialize, which takes its flags out of the list.
    const std::string out = benchmarkFlag(rest, "benchmark_out"), format = benchmarkFlag(rest, "benchmark_out_format"),
                      filter = benchmarkFlag(rest, "benchmark_filter"),
                      consoleFormat = benchmarkFlag(rest, "benchmark_format");
    if (const auto checked = checkBenchmarkFlags(rest, filter, out); !checked) {
        std::cerr << "cavity_bench: " << cavity::flags::printable(checked.error().message) << "\n";
        return 2;
    }
    // Google Benchmark writes --benchmark_out as it goes: it writes a file
    // beside it here, renamed over it once some benchmark has measured
    // something, so that a run that fails or is killed leaves an existing
    // file whole.
    const std::string partial = out.empty() ? std::string() : out + ".partial." + std::to_string(::getpid());
    std::string partialFlag = "--benchmark_out=" + partial;
    for (auto& a : rest)
        if (!out.empty() && std::strncmp(a, "--benchmark_out=", 16) == 0) a = partialFlag.data();
    int n = int(rest.size());
    benchmark::Initialize(&n, rest.data());
    if (benchmark::ReportUnrecognizedArguments(n, rest.data())) return 2;
    // A bad CAVITY_*_BARRIERS is the user's input, not a backend that failed.
    if (auto env = cavity::gpu::withEnvironment({}); !env) {
        std::cerr << "cavity_bench: " << cavity::flags::printable(env.error().message) << "\n";
        return 2;
    }
    options->filter = filter;
    auto registered = cavity::bench::registerSweep(*options);
    if (!registered) {
        std::cerr << "cavity_bench: " << cavity::flags::printable(registered.error().message) << "\n";
        return static_cast<int>(registered.error().code);
    }
    // A JSON file gets one more entry per pass (<id>@<pass>), so that Google
    // Benchmark's compare.py, which judges only a benchmark's time, sees
    // every pass as well (bench/per_pass_reporter.h).
    std::unique_ptr<benchmark::BenchmarkReporter> file;
    if (!out.empty() && (format.empty() || format == "json"))
        file = std::make_unique<cavity::bench::PerPassJsonReporter>();
    // Our console table, unless another format is asked for the console.
    std::unique_ptr<benchmark::BenchmarkReporter> console;
    if (consoleFormat.empty() || consoleFormat == "console") console = std::make_unique<cavity::bench::ConsoleReporter>();
    const size_t ran = benchmark::RunSpecifiedBenchmarks(console.get(), file.get());
    benchmark::Shutdown();
    cavity::bench::releaseBackends();
    file.reset();
    if (!partial.empty()) {
        std::error_code ec;
        if (ran > cavity::bench::failures().size()) std::filesystem::rename(partial, out, ec);
        else std::filesystem::remove(partial, ec);
        if (ec) {
            std::cerr << "cavity_bench: --benchmark_out=" << out << ": cannot be written (" << ec.message() << ")\n";
            return 2;
        }
    }
    return runExitCode(ran, filter);
}
