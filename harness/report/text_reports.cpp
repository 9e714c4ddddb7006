// junit.xml and summary.md (report/gate_report.h).
#include "report/gate_report.h"

#include "report/verdict_text.h"
#include "measure/results.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <unistd.h>

namespace cavity::report {

namespace {

std::string esc(const std::string& s) {
    std::string o;
    for (char ch : s) {
        switch (ch) {
        case '&': o += "&amp;"; break;
        case '<': o += "&lt;"; break;
        case '>': o += "&gt;"; break;
        case '"': o += "&quot;"; break;
        default: o += ch;
        }
    }
    return o;
}

std::string hostName() {
    char name[256] = {};
    return ::gethostname(name, sizeof name - 1) == 0 && name[0] ? name : "localhost";
}

// Seconds as JUnit readers take them: fixed, three decimals.
std::string seconds3(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3f", std::isfinite(x) && x > 0 ? x : 0.0);
    return b;
}

// "rmse 0.0123 > 0.005 at (3,4)" -> {"rmse 0.0123", "> 0.005 at (3,4)"}: the
// summary's result and tolerance columns. A line without a comparator is all result.
std::pair<std::string, std::string> splitFailure(const std::string& f) {
    for (const char* op : {" > ", " < "}) {
        const auto at = f.find(op);
        if (at == std::string::npos) continue;
        std::string result = f.substr(0, at), tolerance = f.substr(at + 3);
        if (const auto where = tolerance.find(" at ("); where != std::string::npos) {
            result += tolerance.substr(where);
            tolerance.resize(where);
        }
        return {result, (op[1] == '>' ? "≤ " : "≥ ") + tolerance};
    }
    return {f, ""};
}

}  // namespace

std::string junitXml(const GateRun& run) {
    int tests = 0, failures = 0, errors = 0, skipped = 0;
    std::ostringstream cases;
    for (const auto* r : ordered(run)) {
        // GitLab shows a failure's element text, Jenkins its message: both
        // carry it. A timing check's time is the pass's median; JUnit times
        // are seconds with at most 3 decimals (the xunit plugin's schema).
        auto testcase = [&](const std::string& name, const std::string& failure, bool isError, double seconds = 0) {
            ++tests;
            cases << "    <testcase classname=\"cavity.gate." << esc(run.matrix) << "\" name=\"" << esc(name)
                  << "\" time=\"" << seconds3(seconds) << "\">";
            if (!failure.empty()) {
                (isError ? errors : failures)++;
                const char* tag = isError ? "error" : "failure";
                cases << "\n      <" << tag << " message=\"" << esc(failure) << "\" type=\"" << tag << "\">" << esc(failure)
                      << "</" << tag << ">\n    ";
            }
            cases << "</testcase>\n";
        };
        const std::string name = r->label();
        if (!r->error.empty()) {
            testcase(name, r->error, true);
            continue;
        }
        const std::string v = r->verdict();
        // An expected failure or a known flake that failed is reported as
        // skipped with its reason: visible, not counted as a failure.
        const bool excused = v == "expected-fail" || v == "known-flake";
        auto check = [&](const std::string& caseName, const std::string& f, double seconds = 0) {
            if (f.empty() || !excused) return testcase(caseName, f, false, seconds);
            ++tests;
            ++skipped;
            cases << "    <testcase classname=\"cavity.gate." << esc(run.matrix) << "\" name=\"" << esc(caseName)
                  << "\" time=\"" << seconds3(seconds) << "\">\n      <skipped message=\"" << esc(verdictNote(*r) + ": " + f)
                  << "\"/>\n    </testcase>\n";
        };
        for (const auto& i : r->images) check(name + "/image/" + i.image, joined(i.failures));
        for (const auto& t : r->timings) {
            std::string f;
            if (!t.passed())
                f = "median " + num(t.medianMs) + " ms > budget " + num(*t.budgetMs) + " ms (+" +
                    num(100 * (t.medianMs / *t.budgetMs - 1), 3) + "%)";
            check(name + "/time/" + t.pass, f, t.medianMs / 1000);
        }
        check(name + "/deterministic", r->deterministic ? "" : "a second frame was not bit-identical");
        if (v == "unexpected-pass") testcase(name + "/expectation", verdictNote(*r), false);
        if (v == "flaky") {
            // Maven Surefire's element for a test that failed and then
            // passed on a rerun (Jenkins and GitLab read it): a pass, marked.
            ++tests;
            cases << "    <testcase classname=\"cavity.gate." << esc(run.matrix) << "\" name=\"" << esc(name + "/flaky")
                  << "\" time=\"0.000\">\n      <flakyFailure message=\"" << esc(verdictNote(*r)) << "\" type=\"flaky\">"
                  << esc(joined(r->firstFailures)) << "</flakyFailure>\n      <system-out>flaky: failed attempt 1, passed attempt "
                  << r->attempts << "</system-out>\n    </testcase>\n";
        }
    }
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" time=\""
      << seconds3(run.seconds) << "\">\n"
      // Ant's schema requires package, id, timestamp, hostname and the
      // properties, system-out and system-err elements; Jenkins' allows them.
      << "  <testsuite name=\"cavity.gate." << esc(run.matrix) << "\" package=\"cavity.gate\" id=\"0\" timestamp=\""
      << utcTimestamp().substr(0, 19) << "\" hostname=\"" << esc(hostName()) << "\" tests=\"" << tests << "\" failures=\""
      << failures << "\" errors=\"" << errors << "\" skipped=\"" << skipped << "\" time=\"" << seconds3(run.seconds)
      << "\">\n    <properties/>\n"
      << cases.str() << "    <system-out/>\n    <system-err/>\n  </testsuite>\n</testsuites>\n";
    return x.str();
}

std::string summaryMarkdown(const GateRun& run) {
    int failed = 0, unbudgeted = 0, nondet = 0, repetitions = 1, noted = 0;
    for (const auto& r : run.results) {
        failed += r.fatal();
        noted += !r.fatal() && r.verdict() != "pass";
        repetitions = std::max(repetitions, r.repetition + 1);
        nondet += !r.deterministic;
        for (const auto& t : r.timings) unbudgeted += !t.budgetMs;
    }
    std::ostringstream m;
    m << "## Cavity gate `" << run.matrix << "`"
      << (run.shardCount > 1 ? " (shard " + std::to_string(run.shardIndex) + "/" + std::to_string(run.shardCount) + ")" : "")
      << ": " << (failed ? "**" + std::to_string(failed) + " of " + std::to_string(run.results.size()) + " configurations failed**"
                  : noted ? "no regression in " + std::to_string(run.results.size()) + " configurations, " + std::to_string(noted) +
                                " reported"
                         : "all " + std::to_string(run.results.size()) + " configurations passed")
      << " (" << num(run.seconds, 3) << " s)\n\n" << countsText(run) << "\n\n";
    for (const auto& e : run.backendErrors) m << "- backend could not start: " << e << "\n";
    if (failed) {
        m << "| configuration | check | result | tolerance |\n| --- | --- | --- | --- |\n";
        int rows = 0;
        for (const auto* r : ordered(run)) {
            if (!r->fatal()) break;
            if (++rows > 40) {
                m << "| … | | more in index.html | |\n";
                break;
            }
            const std::string name = "`" + r->id + "`" + (r->repetition ? " rep " + std::to_string(r->repetition) : "");
            if (!r->error.empty()) m << "| " << name << " | run | " << r->error << " | |\n";
            if (r->verdict() == "unexpected-pass") m << "| " << name << " | expectation | unexpected pass | " << r->expectedWhy << " |\n";
            for (const auto& i : r->images)
                for (const auto& f : i.failures) {
                    const auto [result, tolerance] = splitFailure(f);
                    m << "| " << name << " | " << i.image << " | " << result << " | " << tolerance << " |\n";
                }
            for (const auto& t : r->timings)
                if (!t.passed())
                    m << "| " << name << " | time " << t.pass << " | " << num(t.medianMs) << " ms (+"
                      << num(100 * (t.medianMs / *t.budgetMs - 1), 3) << "%) | ≤ " << num(*t.budgetMs) << " ms |\n";
        }
        m << "\n";
    }
    if (noted) {
        // Not fatal, never silent: flaky configurations, expected failures
        // and known flakes, with what they said.
        m << "| configuration | verdict | note |\n| --- | --- | --- |\n";
        for (const auto* r : ordered(run))
            if (!r->fatal() && r->verdict() != "pass") m << "| `" << r->label() << "` | " << r->verdict() << " | " << verdictNote(*r) << " |\n";
        m << "\n";
    }
    if (repetitions > 1)
        m << "- each configuration was rendered " << repetitions << " times; every repetition is judged on its own and counted above\n";
    if (nondet) m << "- " << nondet << " configurations were not bit-identical across two frames on the same device\n";
    if (unbudgeted) m << "- " << unbudgeted << " pass timings had no budget for this device (reported, not failed)\n";
    m << "\nAccept intended changes with `cavity baselines update --from <gate output>`; details in index.html.\n";
    return m.str();
}

}  // namespace cavity::report
