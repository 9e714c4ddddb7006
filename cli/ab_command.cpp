// `cavity ab --a A --b B`: two builds measured interleaved on one GPU, as
// Chromium's Pinpoint alternates them: round after round, one cavity_bench
// process of each (A then B in odd rounds, B then A in even ones), each with
// its configurations in a shuffled order; then every side's repetitions
// merged and compared pass by pass (cavity compare). Drift of the machine
// over the minutes of a measurement lands on both sides alike, where two
// sequential runs put all of it on one.
#include "cli.h"
#include "core/json_file.h"
#include "core/json_input.h"
#include "measure/results.h"
#include "measure/runner.h"
#include "report/compare_report.h"
#include "staging.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <iostream>
#include <optional>
#include <regex>
#include <set>

#include <cstring>

#include <sys/wait.h>
#include <unistd.h>

namespace cavity::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const CommandSpec& abSpec() {
    static const CommandSpec spec{
        "cavity ab",
        "Measures two builds interleaved on one GPU (A, B, B, A, ... cavity_bench processes, the configurations "
        "shuffled in each), merges each side's repetitions and compares them pass by pass.",
        {
            {"--a", "PATH", "build A: a cavity_bench binary, a build folder (bench/cavity_bench) or a bundle (required)"},
            {"--b", "PATH", "build B, the same (required)"},
            {"--rounds", "N", "processes of each build (2..1000; default 10)"},
            {"--filter", "REGEX", "the configurations to measure (--benchmark_filter of cavity_bench; default all)"},
            {"--bench-args", "ARGS", "more flags for every cavity_bench process, space-separated (--frames 20 --max-time 0.5)"},
            {"--a-args", "ARGS", "more flags for A's processes only, after --bench-args"},
            {"--b-args", "ARGS", "more flags for B's processes only: one build against itself with an edited kernel is "
                                 "--a X --b X --b-args '--kernel-source NAME=FILE'"},
            {"--out", "DIR", "where the runs, a.json, b.json and compare.json go (default out/ab)"},
            {"--min-change", "P|auto", "as cavity compare (default auto)"},
            {"--fail-on-slower", "", "exit 1 when any pass of B is slower than A's"},
            {"--list", "", "print the benchmarks each build would run, with every flag given, and run nothing"},
        },
        "",
        "",
        "\nExit codes: 0 compared, 1 slower with --fail-on-slower, 2 bad input, 4 a cavity_bench process failed.",
        {
            "cavity ab --a main/build --b pr/build --filter 'corner/alchemy_fast/' --rounds 10",
            "cavity ab --a main/.bundle --b pr/.bundle --rounds 6 --bench-args='--max-time 0.5' --fail-on-slower",
            "cavity ab --a build --b build --b-args '--kernel-source ssao_alchemy_fast.glsl=edit.glsl' --filter /alchemy_fast/",
        },
    };
    return spec;
}

Result<std::string> benchBinary(const std::string& flag, const std::string& path) {
    std::error_code ec;
    for (const fs::path& p : {fs::path(path), fs::path(path) / "bench" / "cavity_bench", fs::path(path) / "cavity_bench"})
        if (fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return p.string();
    return badInput(flag + " " + path + ": no cavity_bench there (a binary, a build folder with bench/cavity_bench, "
                                        "or a bundle)");
}

// What a cavity_bench process left: its exit code, and its output where it
// was not sent to a log file.
struct BenchExit {
    int code = 0;
    std::string how;   // "exit 3", "killed by signal 11 (Segmentation fault)"
    std::string output;
};

// One cavity_bench process, its own flags and ours: its stdout and stderr go
// to the file `log`, or, where `log` is empty, come back in the result.
Result<BenchExit> spawnBench(const std::string& exe, const std::vector<std::string>& args, const std::string& log) {
    std::vector<char*> argv{const_cast<char*>(exe.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    int pipe[2] = {-1, -1};
    if (log.empty() && ::pipe(pipe) != 0) return internal("pipe failed");
    const pid_t pid = ::fork();
    if (pid < 0) return internal("fork failed");
    if (pid == 0) {
        if (!log.empty()) {
            if (FILE* f = std::freopen(log.c_str(), "w", stdout)) ::dup2(::fileno(f), 2);
        } else {
            ::dup2(pipe[1], 1);
            ::dup2(pipe[1], 2);
            ::close(pipe[0]);
            ::close(pipe[1]);
        }
        // A bundle's libraries are beside the binary.
        const std::string lib = (fs::path(exe).parent_path() / "lib").string();
        if (fs::is_directory(lib)) ::setenv("LD_LIBRARY_PATH", lib.c_str(), 1);
        ::execv(exe.c_str(), argv.data());
        std::_Exit(127);
    }
    BenchExit e;
    if (log.empty()) {
        ::close(pipe[1]);
        char buf[4096];
        for (ssize_t n; (n = ::read(pipe[0], buf, sizeof buf)) > 0;) e.output.append(buf, size_t(n));
        ::close(pipe[0]);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    e.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (WIFSIGNALED(status)) e.how = "killed by signal " + std::to_string(WTERMSIG(status)) + " (" + ::strsignal(WTERMSIG(status)) + ")";
    else e.how = "exit " + std::to_string(e.code);
    return e;
}

Status runBench(const std::string& exe, const std::vector<std::string>& args, const std::string& log) {
    CAVITY_ASSIGN(const BenchExit e, spawnBench(exe, args, log));
    if (e.code != 0) return internal(exe + " failed (" + e.how + "); see " + log);
    return {};
}

// The benchmarks a side would run (cavity_bench --benchmark_list_tests with
// the same flags), asked before anything is written: a filter that matches
// nothing, or a flag that side refuses, is bad input, not a failed run.
Result<std::string> checkSide(const std::string& exe, const std::string& flag, std::vector<std::string> args) {
    args.insert(args.begin(), "--benchmark_list_tests=true");
    CAVITY_ASSIGN(const BenchExit e, spawnBench(exe, args, ""));
    if (e.code == 0) return e.output;
    std::string last;
    std::istringstream lines(e.output);
    for (std::string l; std::getline(lines, l);)
        if (!l.empty()) last = l;
    const std::string why = flag + " " + exe + ": " + (last.empty() ? e.how : last);
    if (e.code == 2) return badInput(why);
    return internal(why);
}

// The iteration entries of every round's file, each round one repetition. A
// round is a process's own output, so what is wrong with one is a failed
// process (exit 4), said with the file: missing (the process wrote
// elsewhere), not cavity_bench's JSON, or no iteration measured.
Result<json> mergeRounds(const std::vector<std::string>& files) {
    json merged = {{"benchmarks", json::array()}};
    for (size_t r = 0; r < files.size(); ++r) {
        auto doc = readJsonFile(files[r]);
        if (!doc) return internal(doc.error().message);
        const auto& bench = doc->is_object() && doc->contains("benchmarks") ? (*doc)["benchmarks"] : json();
        if (!bench.is_array()) return internal(files[r] + ": not cavity_bench JSON (no list of benchmarks)");
        if (r == 0 && doc->contains("context") && (*doc)["context"].is_object()) merged["context"] = (*doc)["context"];
        size_t measured = 0;
        for (json b : bench) {
            if (!b.is_object()) return internal(files[r] + ": a benchmark entry is not an object: " + core::shortDump(b));
            const json kind = b.contains("run_type") ? b["run_type"] : json("iteration");
            if (!kind.is_string()) return internal(files[r] + ": run_type = " + core::shortDump(kind) + ": must be a string");
            if (kind.get<std::string>() != "iteration") continue;
            b["repetition_index"] = r;
            b["repetitions"] = files.size();
            merged["benchmarks"].push_back(std::move(b));
            ++measured;
        }
        if (measured == 0) return internal(files[r] + ": the process measured nothing (no iteration entries)");
    }
    return merged;
}

// This run's files move in, each replacing its namesake whole (the rounds
// first, compare.json last), and only then do an earlier ab's files that
// this one did not write go (a run of more rounds left more): a kill
// between the moves leaves every file whole, never the earlier results
// deleted with nothing in their place.
Status abFilesMovedIn(const fs::path& staging, const std::string& out) {
    std::error_code ec;
    std::vector<fs::path> made;
    for (const auto& e : fs::directory_iterator(staging, ec)) made.push_back(e.path());
    const auto rank = [](const fs::path& p) {
        const std::string n = p.filename().string();
        return n == "compare.json" ? 2 : n.find('_') == std::string::npos ? 1 : 0;   // rounds, sides, comparison
    };
    std::stable_sort(made.begin(), made.end(), [&](const fs::path& a, const fs::path& b) { return rank(a) < rank(b); });
    std::set<std::string> names;
    for (const auto& p : made) {
        fs::rename(p, fs::path(out) / p.filename(), ec);
        if (ec) return badInput("--out " + out + ": cannot move " + p.filename().string() + " in: " + ec.message());
        names.insert(p.filename().string());
    }
    const std::regex ours("(a|b)(_[0-9]+)?\\.(json|log)|compare\\.json");
    for (const auto& e : fs::directory_iterator(out, ec))
        if (e.is_regular_file() && std::regex_match(e.path().filename().string(), ours) &&
            !names.count(e.path().filename().string()))
            fs::remove(e.path(), ec);
    fs::remove_all(staging, ec);
    return {};
}

struct AbFlags {
    std::string a, b, filter, out = "out/ab";
    std::vector<std::string> benchArgs;
    std::vector<std::string> sideArgs[2];   // --a-args, --b-args
    int rounds = 10;
    CompareThresholds thresholds;
    bool failOnSlower = false;
    bool list = false;   // --list: what each side would run, and nothing run
};

Result<AbFlags> parseAb(const ParsedFlags& p) {
    AbFlags f;
    f.thresholds.autoMinChange = true;
    f.failOnSlower = p.has("--fail-on-slower");
    f.list = p.has("--list");
    for (const auto& [flag, v] : p.values) {
        if (flag == "--a") {
            CAVITY_ASSIGN(f.a, benchBinary(flag, v));
        } else if (flag == "--b") {
            CAVITY_ASSIGN(f.b, benchBinary(flag, v));
        } else if (flag == "--rounds") {
            CAVITY_ASSIGN(f.rounds, parseInt(flag, v, 2, 1000));
        } else if (flag == "--filter") {
            CAVITY_ASSIGN(const auto checked, parseFilter(flag, v));
            (void)checked;
            f.filter = v;
        } else if (flag == "--out") {
            f.out = v;
        } else if (flag == "--bench-args" || flag == "--a-args" || flag == "--b-args") {
            auto& to = flag == "--bench-args" ? f.benchArgs : f.sideArgs[flag == "--a-args" ? 0 : 1];
            std::istringstream words(v);
            for (std::string w; words >> w;) {
                // ab sets these itself: one repetition a process, written where it reads it.
                static const std::set<std::string> own = {"--benchmark_out", "--benchmark_out_format",
                                                          "--benchmark_repetitions", "--benchmark_filter",
                                                          "--benchmark_list_tests", "--benchmark_enable_random_interleaving"};
                if (own.count(w.substr(0, w.find('='))))
                    return badInput(flag + " " + w + ": cavity ab sets " + w.substr(0, w.find('=')) +
                                    " itself (use --filter and --rounds)");
                to.push_back(w);
            }
            if (to.empty()) return badInput(flag + " '" + v + "': no flags in it");
        } else if (flag == "--min-change" && v != "auto") {
            f.thresholds.autoMinChange = false;
            CAVITY_ASSIGN(f.thresholds.minChangePct,
                          parseNumber(flag, v, [](double x) { return x >= 0; }, "a percentage >= 0, or auto"));
        }
    }
    if (f.a.empty() || f.b.empty()) return badInput(std::string(f.a.empty() ? "--a" : "--b") + ": required (a build to measure)");
    return f;
}

}  // namespace

int abCommand(const std::vector<std::string>& argv) {
    const std::string program = "cavity ab";
    auto parsed = parseFlags(abSpec(), argv);
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    auto f = parseAb(*parsed);
    if (!f) return fail(program, f.error());
    if (auto st = checkWritableDir("--out", f->out); !st) return fail(program, st.error());
    for (int side = 0; side < 2; ++side) {
        std::vector<std::string> args;
        if (!f->filter.empty()) args.push_back("--benchmark_filter=" + f->filter);
        args.insert(args.end(), f->benchArgs.begin(), f->benchArgs.end());
        args.insert(args.end(), f->sideArgs[side].begin(), f->sideArgs[side].end());
        auto listed = checkSide(side == 0 ? f->a : f->b, side == 0 ? "--a" : "--b", args);
        if (!listed) return fail(program, listed.error());
        if (f->list) std::cout << (side == 0 ? "A: " : "B: ") << (side == 0 ? f->a : f->b) << "\n" << *listed;
    }
    if (f->list) return 0;
    // Every round, the merged sides and the comparison are written under a
    // staging folder and replace what --out held only once all are there: a
    // failed or killed ab leaves --out as it was (a failed process's log
    // stays in the staging folder it names, until the next ab there).
    std::error_code ec;
    fs::create_directories(f->out, ec);
    if (ec) return fail(program, badInput("--out " + f->out + ": cannot be created: " + ec.message()));
    const fs::path staging = stagingDir(f->out);
    fs::create_directories(staging, ec);
    if (ec) return fail(program, badInput("--out " + f->out + ": cannot be written: " + ec.message()));
    std::vector<std::string> files[2];
    for (int r = 0; r < f->rounds; ++r) {
        // A B, then B A: a drift within a round falls on both sides alike.
        for (int k = 0; k < 2; ++k) {
            const int side = r % 2 == 0 ? k : 1 - k;
            const std::string name = std::string(side == 0 ? "a" : "b") + "_" + std::to_string(r);
            const std::string out = (staging / (name + ".json")).string();
            std::vector<std::string> args = {"--benchmark_repetitions=1", "--benchmark_enable_random_interleaving=true",
                                             "--benchmark_out=" + out, "--benchmark_out_format=json"};
            if (!f->filter.empty()) args.push_back("--benchmark_filter=" + f->filter);
            args.insert(args.end(), f->benchArgs.begin(), f->benchArgs.end());
            args.insert(args.end(), f->sideArgs[side].begin(), f->sideArgs[side].end());
            std::cerr << "cavity ab: round " << r + 1 << "/" << f->rounds << ": " << (side == 0 ? "A" : "B") << "\n";
            if (auto st = runBench(side == 0 ? f->a : f->b, args, (staging / (name + ".log")).string()); !st)
                return fail(program, st.error());
            files[side].push_back(out);
        }
    }
    std::optional<SampleSets> sides[2];
    for (int side = 0; side < 2; ++side) {
        auto merged = mergeRounds(files[side]);
        if (!merged) return fail(program, merged.error());
        const std::string path = (staging / (side == 0 ? "a.json" : "b.json")).string();
        if (auto st = writeJson(path, *merged); !st) return fail(program, st.error());
        auto sets = loadSampleSets(path);
        if (!sets) return fail(program, sets.error());
        // Named where it will be once the staging folder is moved in, as
        // compare.json and the table record it.
        sets->path = (fs::path(f->out) / (side == 0 ? "a.json" : "b.json")).string();
        sides[side] = std::move(*sets);
    }
    const auto rows = compareAll(*sides[0], *sides[1], f->thresholds);
    // Two sides with nothing in common (--a-args '--backend gl' against
    // --b-args '--backend vk') compared nothing: not "0 slower", exit 0.
    if (std::none_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict != "new" && r.verdict != "gone"; }))
        return fail(program, badInput("A and B measured no configuration and pass in common (" + std::to_string(rows.size()) +
                                      " on one side only): give both sides the same selection; their runs are in " +
                                      staging.string()));
    if (auto st = writeJson((staging / "compare.json").string(), compareJson(rows, *sides[0], *sides[1], f->thresholds)); !st)
        return fail(program, st.error());
    if (auto st = abFilesMovedIn(staging, f->out); !st) return fail(program, st.error());
    std::cout << compareTable(rows, *sides[0], *sides[1], f->thresholds);
    const bool anySlower = std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict == "slower"; });
    return f->failOnSlower && anySlower ? 1 : 0;
}

}  // namespace cavity::cli
