#include "gate_report.h"

#include "results.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace cavity::gate {

namespace fs = std::filesystem;

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

std::string reportHtml(const GateRun& run, const std::string& chartsDir) {
    std::ostringstream h;
    int failed = 0;
    for (const auto& r : run.results) failed += r.fatal();
    h << R"html(<!doctype html><html><head><meta charset="utf-8"><title>Cavity gate )html" << esc(run.matrix)
      << (failed ? ": " + std::to_string(failed) + " failed" : std::string(": passed")) << R"html(</title>
<style>
body{font:14px system-ui,sans-serif;margin:16px;background:#1b1d21;color:#e6e6e6}
h1{font-size:20px} h2{font-size:15px;margin:0 0 6px 0;font-family:monospace}
.cfg{border:1px solid #3a3d44;border-radius:6px;padding:10px;margin:10px 0;background:#23262b}
.fail{border-color:#e05252} .badge{display:inline-block;padding:1px 8px;border-radius:10px;font-size:12px;margin-left:6px}
.pass .badge{background:#2e7d32} .fail .badge{background:#c62828} .noted .badge{background:#a66f00}
.row{display:flex;gap:10px;flex-wrap:wrap;align-items:flex-start;margin:6px 0}
figure{margin:0} figcaption{font-size:12px;color:#aaa}
.zoomable img{image-rendering:pixelated;border:1px solid #444}
.cmp{position:relative;display:inline-block} .cmp img{display:block}
.cmp .top{position:absolute;top:0;left:0;overflow:hidden}
table{border-collapse:collapse;font-size:12px} td,th{border:1px solid #3a3d44;padding:2px 6px;text-align:right}
td.l,th.l{text-align:left} .bad{color:#ff6b6b;font-weight:bold}
.controls{position:sticky;top:0;background:#1b1d21;padding:6px 0;z-index:2}
.thumb{width:120px;image-rendering:auto;border:1px solid #444}
.scale{height:8px;width:100%;margin-top:2px;border:1px solid #444}
.scalelabels{display:flex;justify-content:space-between;font-size:11px;color:#aaa}
</style></head><body>
<div class="controls"><b>Cavity gate</b> matrix <code>)html"
      << esc(run.matrix) << "</code> · " << run.results.size() << " configurations · <span class=\""
      << (failed ? "bad" : "") << "\">" << failed << " failed</span> · " << esc(countsText(run)) << " · " << num(run.seconds, 3)
      << R"html( s · zoom <input id="zoom" type="range" min="1" max="8" value="2" oninput="setZoom(this.value)"> <span id="zv">2x</span></div>
)html";
    for (const auto& e : run.backendErrors) h << "<p class=bad>backend could not start: " << esc(e) << "</p>\n";
    int n = 0;
    for (const auto* r : ordered(run)) {
        const std::string v = r->verdict();
        h << "<div class=\"cfg " << (r->fatal() ? "fail" : v == "pass" ? "pass" : "noted") << "\" data-id=\"" << esc(r->id)
          << "\" data-repetition=\"" << r->repetition << "\" data-verdict=\"" << v << "\"><h2>" << esc(r->label())
          << "<span class=badge>" << (v == "fail" ? "FAIL" : v) << "</span></h2>\n";
        if (!r->error.empty()) h << "<p class=bad>" << esc(r->error) << "</p>\n";
        if (const std::string note = verdictNote(*r); !note.empty()) h << "<p class=bad>" << esc(note) << "</p>\n";
        if (!r->deterministic) h << "<p class=bad>not bit-identical across two frames on this device</p>\n";
        if (r->passed()) {
            // A passing configuration gets thumbnails of what it rendered and
            // its worst numbers: the page stays small enough to open
            // (every image of every passing ci configuration embedded in full
            // made 8.4 MB), and a reviewer's eye goes to the failures.
            h << "<div class=row>";
            for (const auto& i : r->images) {
                h << "<figure><figcaption>" << esc(i.image);
                if (i.metrics) h << " · max " << num(i.metrics->maxAbs, 2) << " · SSIM " << num(i.metrics->ssim, 5);
                h << "</figcaption><img class=thumb src=\"" << dataUri(i.newPng) << "\"></figure>";
            }
            h << "</div>\n";
        }
        for (const auto& i : r->images) {
            if (r->passed()) break;
            ++n;
            const std::string base = dataUri(i.baselinePng), now = dataUri(i.newPng), diff = dataUri(i.diffPng);
            h << "<div class=row><figure class=zoomable><figcaption>" << esc(i.image) << " baseline</figcaption>"
              << (base.empty() ? "<p class=bad>missing</p>" : "<img class=z src=\"" + base + "\">") << "</figure>"
              << "<figure class=zoomable><figcaption>new</figcaption><img class=z src=\"" << now << "\"></figure>"
              << "<figure class=zoomable><figcaption>|new - baseline|</figcaption>"
              << (diff.empty() ? "" : "<img class=z src=\"" + diff + "\">")
              << "<div class=scale style=\"background:" << heatScaleCss() << "\"></div><div class=scalelabels><span>0</span><span>"
              << num(i.tolerance.pixelThreshold) << "</span><span>≥ " << num(2 * i.tolerance.pixelThreshold)
              << "</span></div></figure>";
            if (!base.empty())
                h << "<figure class=zoomable><figcaption>baseline ◀ slider ▶ new</figcaption><div class=cmp><img class=z src=\""
                  << now << "\"><div class=top id=t" << n << "><img class=z src=\"" << base
                  << "\"></div></div><input type=range min=0 max=100 value=50 oninput=\"slide(" << n
                  << ",this.value)\"></figure>";
            h << "<table><tr><th class=l>metric</th><th>value</th><th>tolerance</th></tr>";
            if (i.metrics) {
                const auto& m = *i.metrics;
                const auto& t = i.tolerance;
                auto row = [&](const char* name, double v, double tol, bool upper, const char* unit = "") {
                    const bool bad = upper ? v > tol : v < tol;
                    h << "<tr><td class=l>" << name << "</td><td class=\"" << (bad ? "bad" : "") << "\">" << num(v) << unit
                      << "</td><td>" << (upper ? "≤ " : "≥ ") << num(tol) << unit << "</td></tr>";
                };
                row("max abs", m.maxAbs, t.maxAbs, true);
                row("mean abs", m.meanAbs, t.meanAbs, true);
                row("RMSE", m.rmse, t.rmse, true);
                row("PSNR", m.psnr, t.psnrMin, false, " dB");
                row("pixels over threshold", 100 * m.overThresholdShare, 100 * t.overThresholdShare, true, "%");
                row("SSIM", m.ssim, t.ssimMin, false);
                if (m.flipMean >= 0) row("FLIP mean", m.flipMean, t.flipMeanMax, true);
                if (m.flipMean >= 0)
                    row(("pixels differing by > " + num(t.differingDelta) + " steps").c_str(), 100 * m.differingShare,
                        100 * t.differingShareMax, true, "%");
                if (m.nonFinite) h << "<tr><td class=l>non-finite</td><td class=bad>" << m.nonFinite << "</td><td>0</td></tr>";
            }
            h << "</table></div>\n";
            for (const auto& f : i.failures) h << "<div class=bad>" << esc(i.image) << ": " << esc(f) << "</div>\n";
        }
        if (!r->timings.empty()) {
            h << "<table><tr><th class=l>pass</th><th>median ms</th><th>budget ms</th><th>clock</th></tr>";
            for (const auto& t : r->timings)
                h << "<tr><td class=l>" << esc(t.pass) << "</td><td class=\"" << (t.passed() ? "" : "bad") << "\">"
                  << num(t.medianMs) << "</td><td>" << (t.budgetMs ? num(*t.budgetMs) : "none for this device")
                  << "</td><td>" << esc(t.clock) << "</td></tr>";
            h << "</table>\n";
        }
        h << "</div>\n";
    }
    // Charts from scripts/charts.py, when a benchmark run left them next to the report.
    std::ifstream idx(fs::path(chartsDir) / "index.json");
    if (idx) {
        h << "<h1>Benchmark charts</h1><div class=row>";
        for (const auto& entry : fs::directory_iterator(chartsDir))
            if (entry.path().extension() == ".png")
                h << "<figure><figcaption>" << esc(entry.path().stem().string()) << "</figcaption><img width=640 src=\""
                  << dataUri(entry.path().string()) << "\"></figure>";
        h << "</div>";
    }
    h << R"html(<script>
function setZoom(z){document.getElementById('zv').textContent=z+'x';
 document.querySelectorAll('img.z').forEach(function(i){ if(!i.dataset.w){i.dataset.w=i.naturalWidth;}
  i.style.width=(i.dataset.w*z)+'px';});
 document.querySelectorAll('.cmp .top').forEach(function(t){t.style.height='100%';});}
function slide(n,v){var t=document.getElementById('t'+n);t.style.width=v+'%';}
window.addEventListener('load',function(){setZoom(2);document.querySelectorAll('.cmp .top').forEach(function(t){t.style.width='50%';});});
</script></body></html>
)html";
    return h.str();
}

Status writeReports(const GateRun& run, const std::string& outDir) {
    const fs::path out(outDir);
    std::error_code ec;
    fs::create_directories(out, ec);
    CAVITY_TRY(writeJson((out / "gate.json").string(), toJson(run)));
    CAVITY_TRY(writeText(out / "junit.xml", junitXml(run)));
    CAVITY_TRY(writeText(out / "summary.md", summaryMarkdown(run)));
    CAVITY_TRY(writeText(out / "index.html", reportHtml(run, (out / "charts").string())));
    return {};
}

}  // namespace cavity::gate
