#include "report/gate_report.h"

#include "measure/results.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

namespace cavity::report {

namespace fs = std::filesystem;

// harness/report/'s files by name, embedded at build time (cmake/embed.cmake).
const std::map<std::string, std::string>& reportFiles();

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

std::string num(double x, int digits = 4) {
    if (!std::isfinite(x) || x >= 1e299) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.*g", digits, x);
    return b;
}

// What fails the gate first, then what is reported but not fatal (flaky,
// expected failures, known flakes), then the plain passes; by id within.
int rank(const ConfigResult& r) { return r.fatal() ? 0 : r.verdict() != "pass" ? 1 : 2; }

std::vector<const ConfigResult*> ordered(const GateRun& run) {
    std::vector<const ConfigResult*> v;
    for (const auto& r : run.results) v.push_back(&r);
    std::stable_sort(v.begin(), v.end(), [](auto* a, auto* b) {
        if (rank(*a) != rank(*b)) return rank(*a) < rank(*b);
        return a->id < b->id;
    });
    return v;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += (s.empty() ? "" : "; ") + l;
    return s;
}

// One line for a verdict that is not a plain pass or fail.
std::string verdictNote(const ConfigResult& r) {
    const std::string v = r.verdict();
    if (v == "flaky")
        return "flaky: passed on attempt " + std::to_string(r.attempts) + ", attempt 1 failed: " + joined(r.firstFailures);
    if (v == "expected-fail") return "expected failure (" + r.expectedWhy + ")";
    if (v == "known-flake")
        return "known flake, failed all " + std::to_string(r.attempts) + " attempts (" + r.expectedWhy + ")";
    if (v == "unexpected-pass") return "unexpected pass: listed as an expected failure (" + r.expectedWhy + "); remove the entry";
    return "";
}

// "3 passed, 1 flaky, ...": every verdict that occurred, in a fixed order.
std::string countsText(const GateRun& run) {
    const auto c = run.counts();
    std::string s;
    for (const char* v : {"fail", "error", "unexpected-pass", "flaky", "known-flake", "expected-fail", "pass"}) {
        const auto it = c.find(v);
        if (it == c.end()) continue;
        const std::string word = std::string(v) == "pass" ? "passed" : std::string(v) == "fail" ? "failed" : v;
        s += (s.empty() ? "" : ", ") + std::to_string(it->second) + " " + word;
    }
    return s;
}

std::string base64File(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return "";
    const std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string o;
    size_t i = 0;
    for (; i + 2 < data.size(); i += 3) {
        const unsigned v = (unsigned char)data[i] << 16 | (unsigned char)data[i + 1] << 8 | (unsigned char)data[i + 2];
        o += t[v >> 18 & 63];
        o += t[v >> 12 & 63];
        o += t[v >> 6 & 63];
        o += t[v & 63];
    }
    if (i < data.size()) {
        unsigned v = (unsigned char)data[i] << 16;
        if (i + 1 < data.size()) v |= (unsigned char)data[i + 1] << 8;
        o += t[v >> 18 & 63];
        o += t[v >> 12 & 63];
        o += i + 1 < data.size() ? t[v >> 6 & 63] : '=';
        o += '=';
    }
    return o;
}

std::string dataUri(const std::string& png) {
    const std::string b = png.empty() ? "" : base64File(png);
    return b.empty() ? "" : "data:image/png;base64," + b;
}

Status writeText(const fs::path& path, const std::string& text) {
    const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream f(tmp);
        if (!f) return badInput(path.string() + ": cannot write");
        f << text;
        if (!f) return internal("write " + path.string() + " failed");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) return internal("rename " + tmp.string() + ": " + ec.message());
    return {};
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

// The heat-map's colour scale as a CSS gradient, from the colours it is drawn with.
std::string heatScaleCss() {
    std::string g = "linear-gradient(to right";
    for (int k = 0; k <= 8; ++k) {
        const auto c = metrics::heatColor(k / 8.0);
        char b[48];
        std::snprintf(b, sizeof b, ",rgb(%d,%d,%d)", int(255 * c[0] + 0.5f), int(255 * c[1] + 0.5f), int(255 * c[2] + 0.5f));
        g += b;
    }
    return g + ")";
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
            if (rank(*r) == 1) m << "| `" << r->label() << "` | " << r->verdict() << " | " << verdictNote(*r) << " |\n";
        m << "\n";
    }
    if (repetitions > 1)
        m << "- each configuration was rendered " << repetitions << " times; every repetition is judged on its own and counted above\n";
    if (nondet) m << "- " << nondet << " configurations were not bit-identical across two frames on the same device\n";
    if (unbudgeted) m << "- " << unbudgeted << " pass timings had no budget for this device (reported, not failed)\n";
    m << "\nAccept intended changes with `cavity baselines update --from <gate output>`; details in index.html.\n";
    return m.str();
}

namespace {

// The PNG files the page shows, by the path gate.json names them: a passing
// configuration's new images (thumbnails), a failing or noted one's
// baseline, new image and heat-map. Every image of every passing ci
// configuration embedded in full made 8.4 MB.
nlohmann::json shownImages(const GateRun& run) {
    nlohmann::json images = nlohmann::json::object();
    auto add = [&](const std::string& png) {
        if (png.empty() || images.contains(png)) return;
        if (const std::string uri = dataUri(png); !uri.empty()) images[png] = uri;
    };
    for (const auto& r : run.results)
        for (const auto& i : r.images) {
            add(i.newPng);
            if (r.passed()) continue;
            add(i.baselinePng);
            add(i.diffPng);
        }
    return images;
}

// Charts from scripts/charts.py, when a benchmark run left them (and their
// index.json) next to the report; by name.
nlohmann::json charts(const std::string& chartsDir) {
    nlohmann::json out = nlohmann::json::array();
    std::error_code ec;
    if (!fs::exists(fs::path(chartsDir) / "index.json", ec)) return out;
    std::vector<fs::path> pngs;
    for (const auto& entry : fs::directory_iterator(chartsDir, ec))
        if (entry.path().extension() == ".png") pngs.push_back(entry.path());
    std::sort(pngs.begin(), pngs.end());
    for (const auto& png : pngs) out.push_back({{"name", png.stem().string()}, {"src", dataUri(png.string())}});
    return out;
}

// JSON inside <script>: every '<', '>' and '&' (which JSON holds only inside
// strings) as a \u escape, so that no "</script>" or "<!--" in a message or
// a path can end the block or change how it is parsed.
std::string scriptSafe(const std::string& json) {
    std::string o;
    o.reserve(json.size());
    for (char ch : json) {
        switch (ch) {
        case '<': o += "\\u003c"; break;
        case '>': o += "\\u003e"; break;
        case '&': o += "\\u0026"; break;
        default: o += ch;
        }
    }
    return o;
}

// Replaces the one occurrence of `marker` in `page`.
Status fill(std::string& page, const std::string& marker, const std::string& text) {
    const auto at = page.find(marker);
    if (at == std::string::npos || page.find(marker, at + 1) != std::string::npos)
        return internal("harness/report/index.html: needs " + marker + " exactly once");
    page.replace(at, marker.size(), text);
    return {};
}

}  // namespace

nlohmann::json reportData(const GateRun& run, const std::string& chartsDir) {
    nlohmann::json order = nlohmann::json::array(), results = nlohmann::json::array();
    for (const auto* r : ordered(run)) order.push_back(r - run.results.data());
    for (const auto& r : run.results) results.push_back({{"label", r.label()}, {"note", verdictNote(r)}});
    return {{"gate", toJson(run)},
            {"view",
             {{"counts", countsText(run)},
              {"order", order},
              {"results", results},
              {"images", shownImages(run)},
              {"heat_scale", heatScaleCss()},
              {"charts", charts(chartsDir)}}}};
}

Result<std::string> reportHtml(const GateRun& run, const std::string& chartsDir) {
    const auto& files = reportFiles();
    std::string page = files.at("index.html");
    // A message or a path that is not UTF-8 is written with U+FFFD rather
    // than failing the report.
    const std::string data = reportData(run, chartsDir).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    CAVITY_TRY(fill(page, "<script src=\"report.js\"></script>", "<script>\n" + files.at("report.js") + "</script>"));
    CAVITY_TRY(fill(page, "@GATE_DATA@", scriptSafe(data)));
    return page;
}

Status writeReports(const GateRun& run, const std::string& outDir) {
    const fs::path out(outDir);
    std::error_code ec;
    fs::create_directories(out, ec);
    CAVITY_TRY(writeJson((out / "gate.json").string(), toJson(run)));
    CAVITY_TRY(writeText(out / "junit.xml", junitXml(run)));
    CAVITY_TRY(writeText(out / "summary.md", summaryMarkdown(run)));
    CAVITY_ASSIGN(const std::string html, reportHtml(run, (out / "charts").string()));
    CAVITY_TRY(writeText(out / "index.html", html));
    return {};
}

}  // namespace cavity::report
