// junit.xml (report/gate_report.h).
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

// The replaced kernel sources as the suite's properties ("kernel_source.NAME":
// "FILE DIGEST"), or none.
std::string junitProperties(const GateRun& run) {
    if (run.replaced.empty()) return "<properties/>";
    std::string p = "<properties>\n";
    for (const auto& r : run.replaced)
        p += "      <property name=\"kernel_source." + esc(r.name) + "\" value=\"" + esc(r.file + " " + r.digest) + "\"/>\n";
    return p + "    </properties>";
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
      << "\">\n    " << junitProperties(run) << "\n"
      << cases.str() << "    <system-out/>\n    <system-err/>\n  </testsuite>\n</testsuites>\n";
    return x.str();
}

}  // namespace cavity::report
