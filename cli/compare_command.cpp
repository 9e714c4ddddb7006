// `cavity compare OLD NEW`: per configuration and pass, both medians, the
// Hodges-Lehmann change with its interval, the Mann-Whitney U p-value and a
// verdict (compare_verdict.h). OLD and NEW are each a results.json or the
// Google Benchmark JSON of cavity_bench, in any pairing.
#include "cli.h"
#include "report/compare_report.h"
#include "measure/results.h"

#include <filesystem>
#include <algorithm>
#include <optional>
#include <regex>
#include <iostream>

namespace cavity::cli {

namespace {

const CommandSpec& compareSpec() {
    static const CommandSpec spec{
        "cavity compare",
        "Compares two runs pass by pass: change of the median, its interval (Hodges-Lehmann) and a verdict "
        "(Mann-Whitney U test).",
        {
            {"--alpha", "A", "significance of the U test, and 1 - A the confidence of the interval; in (0, 1) (default 0.05)"},
            {"--min-change", "P|auto",
             "smallest change, in percent of the old median, called slower or faster; >= 0 (default 2); auto: each "
             "pass's detectable change (its interval's half-width or the timer's step), from 0.5 up to 2"},
            {"--json", "FILE", "also write the rows as cavity.compare/1 JSON"},
            {"--filter", "REGEX",
             "only the rows whose \"<configuration id> <pass>\" matches (searched): '/alchemy_fast/', ' ao$'"},
            {"--fail-on-slower", "", "exit 1 when any row is slower"},
        },
        "OLD.json NEW.json",
        "a results.json (cavity run) or Google Benchmark JSON (cavity_bench --benchmark_out), each",
        "\nVerdicts: slower, faster, same, inconclusive (with its reason and what to do: too few samples, clocks "
        "differ, mixed clocks, interval too wide, SM clock differs, software renderer), new, gone.\n"
        "Exit codes: 0 compared, 1 slower with --fail-on-slower, 2 bad usage or input.",
        {
            "cavity compare main/results.json pr/results.json",
            "cavity compare --min-change 1 --fail-on-slower main.json pr.json",
            "cavity compare --min-change auto main.json pr.json",
            "cavity compare --json out/compare.json old.json new.json",
            "cavity compare --filter '/alchemy_fast/.* ao$' main.json pr.json",
        },
    };
    return spec;
}

struct CompareFlags {
    std::vector<std::string> files;   // OLD.json NEW.json
    CompareThresholds thresholds;
    std::string jsonPath;
    std::optional<std::regex> filter;
    bool failOnSlower = false;
    std::string helpText;             // --help: print this, compare nothing
};

Result<CompareFlags> parse(const std::vector<std::string>& argv) {
    CompareFlags f;
    CAVITY_ASSIGN(const ParsedFlags parsed, parseFlags(compareSpec(), argv));
    if (parsed.help) {
        f.helpText = parsed.helpText;
        return f;
    }
    f.files = parsed.positionals;
    f.failOnSlower = parsed.has("--fail-on-slower");
    for (const auto& [flag, v] : parsed.values) {
        if (flag == "--json") {
            f.jsonPath = v;
        } else if (flag == "--filter") {
            CAVITY_ASSIGN(f.filter, parseFilter(flag, v));
        } else if (flag == "--alpha") {
            CAVITY_ASSIGN(f.thresholds.alpha,
                          parseNumber(flag, v, [](double x) { return x > 0 && x < 1; }, "a number in (0, 1)"));
        } else if (flag == "--min-change" && v == "auto") {
            f.thresholds.autoMinChange = true;
        } else if (flag == "--min-change") {
            CAVITY_ASSIGN(f.thresholds.minChangePct,
                          parseNumber(flag, v, [](double x) { return x >= 0; }, "a percentage >= 0, or auto"));
        }
    }
    if (f.files.size() != 2)
        return badInput("need two files, OLD.json NEW.json (have " + std::to_string(f.files.size()) +
                        "; see cavity compare --help)");
    // The verdicts written over a file compared would lose that run.
    std::error_code ec;
    for (const auto& file : f.files)
        if (!f.jsonPath.empty() && std::filesystem::equivalent(f.jsonPath, file, ec))
            return badInput("--json " + f.jsonPath + ": is " + file + ", a file compared (give the verdicts a file of their own)");
    return f;
}

}  // namespace

int compareCommand(const std::vector<std::string>& argv) {
    const std::string program = "cavity compare";
    auto parsed = parse(argv);
    if (!parsed) return fail(program, parsed.error());
    if (!parsed->helpText.empty()) {
        std::cout << parsed->helpText;
        return 0;
    }
    const auto& [files, t, jsonPath, filter, failOnSlower, help] = *parsed;
    auto before = loadSampleSets(files[0]);
    if (!before) return fail(program, before.error());
    auto after = loadSampleSets(files[1]);
    if (!after) return fail(program, after.error());
    // One file on both sides compares nothing: every pass would read "same".
    std::error_code ec;
    if (std::filesystem::equivalent(files[0], files[1], ec))
        return fail(program, badInput(files[1] + ": the same file as " + files[0] +
                                      " (compare the old run with the new one, two files)"));

    auto rows = compareAll(*before, *after, t);
    // Nothing compared is no verdict: two runs with no (configuration, pass)
    // in common, or with none measured, would print "0 slower" and exit 0.
    const auto compared = [](const auto& r) { return r.verdict != "new" && r.verdict != "gone"; };
    if (std::none_of(rows.begin(), rows.end(), compared))
        return fail(program, badInput(files[0] + " and " + files[1] + ": no configuration and pass measured in both (" +
                                      std::to_string(rows.size()) + " in one only); compare runs of the same sweep"));
    if (filter) {
        std::erase_if(rows, [&](const auto& r) { return !std::regex_search(r.id + " " + r.pass, *filter); });
        if (std::none_of(rows.begin(), rows.end(), compared))
            return fail(program, badInput("--filter: matches no \"<configuration id> <pass>\" measured in both runs"));
    }
    // The JSON first: if it cannot be written the command fails before it
    // has printed a table that looks like success.
    if (!jsonPath.empty()) {
        if (auto s = writeJson(jsonPath, compareJson(rows, *before, *after, t)); !s) {
            if (s.error().code == ErrorCode::BadInput) return fail(program, badInput("--json " + s.error().message));
            return fail(program, {s.error().code, "--json " + s.error().message});
        }
    }
    std::cout << compareTable(rows, *before, *after, t);
    const bool anySlower = std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict == "slower"; });
    return failOnSlower && anySlower ? 1 : 0;
}

}  // namespace cavity::cli
