// `cavity compare OLD NEW`: per configuration and pass, both medians, the
// Hodges-Lehmann change with its interval, the Mann-Whitney U p-value and a
// verdict (compare_verdict.h). OLD and NEW are each a results.json or the
// Google Benchmark JSON of cavity_bench, in any pairing.
#include "cli.h"
#include "compare_report.h"
#include "results.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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
            {"--min-change", "P", "smallest change, in percent of the old median, called slower or faster; >= 0 (default 2)"},
            {"--json", "FILE", "also write the rows as cavity.compare/1 JSON"},
            {"--fail-on-slower", "", "exit 1 when any row is slower"},
        },
        "OLD.json NEW.json",
        "a results.json (cavity run) or Google Benchmark JSON (cavity_bench --benchmark_out), each",
        "\nExit codes: 0 compared, 1 slower with --fail-on-slower, 2 bad usage or input.",
    };
    return spec;
}

int fail(const std::string& message) {
    std::cerr << "cavity compare: " << message << "\n";
    return 2;
}

Result<double> number(const std::string& flag, const std::string& text, double lo, double hi, bool openLo,
                      const std::string& allowed) {
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    const bool ok = !text.empty() && end && *end == '\0' && std::isfinite(x) && (openLo ? x > lo : x >= lo) && x < hi;
    if (!ok) return badInput(flag + " " + text + ": must be " + allowed);
    return x;
}

}  // namespace

int compareCommand(const std::vector<std::string>& argv) {
    std::vector<std::string> files;
    CompareThresholds t;
    std::string jsonPath;
    bool failOnSlower = false;
    auto parsed = parseFlags(compareSpec(), argv);
    if (!parsed) return fail(parsed.error().message);
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    files = parsed->positionals;
    failOnSlower = parsed->has("--fail-on-slower");
    for (const auto& [flag, v] : parsed->values) {
        if (flag == "--json") {
            jsonPath = v;
            continue;
        }
        auto x = flag == "--alpha" ? number(flag, v, 0, 1, true, "a number in (0, 1)")
                                   : number(flag, v, 0, HUGE_VAL, false, "a percentage >= 0");
        if (!x) return fail(x.error().message);
        (flag == "--alpha" ? t.alpha : t.minChangePct) = *x;
    }
    if (files.size() != 2)
        return fail("need two files, OLD.json NEW.json (have " + std::to_string(files.size()) +
                    "; see cavity compare --help)");
    auto before = loadSampleSets(files[0]);
    if (!before) return fail(before.error().message);
    auto after = loadSampleSets(files[1]);
    if (!after) return fail(after.error().message);

    const auto rows = compareAll(*before, *after, t);
    // The JSON first: if it cannot be written the command fails before it
    // has printed a table that looks like success.
    if (!jsonPath.empty()) {
        if (auto s = writeJson(jsonPath, compareJson(rows, *before, *after, t)); !s) {
            if (s.error().code == ErrorCode::BadInput) return fail("--json " + jsonPath + ": cannot be written");
            std::cerr << "cavity compare: --json " << s.error().message << "\n";
            return exitCode(s.error());
        }
    }
    std::cout << compareTable(rows, *before, *after, t);
    const bool anySlower = std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict == "slower"; });
    return failOnSlower && anySlower ? 1 : 0;
}

}  // namespace cavity::cli
