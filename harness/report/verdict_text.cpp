#include "report/verdict_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cavity::report {

namespace {

int rank(const ConfigResult& r) { return r.fatal() ? 0 : r.verdict() != "pass" ? 1 : 2; }

}  // namespace

std::string num(double x, int digits) {
    if (!std::isfinite(x) || x >= 1e299) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.*g", digits, x);
    return b;
}

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

std::string verdictNote(const ConfigResult& r) {
    const std::string v = r.verdict();
    if (v == "flaky")
        return "flaky: passed on attempt " + std::to_string(r.attempts) + ", attempt 1 failed: " + joined(r.firstFailures);
    if (v == "expected-fail") return "expected failure (" + r.expectedWhy + ")";
    if (v == "known-flake")
        return "known flake, failed all " + std::to_string(r.attempts) + " attempts (" + r.expectedWhy + ")";
    if (v == "unexpected-pass") return "unexpected pass: listed as an expected failure (" + r.expectedWhy + "); remove the entry";
    // A failure that is the intended result of a change is accepted one
    // configuration at a time, by the command the card prints.
    if (v == "fail" && r.error.empty())
        return "to accept this configuration alone: cavity baselines update --filter '^" + r.id +
               "$' (its images become the baselines), or cavity baselines approve --filter '^" + r.id +
               "$' --why '...' (its digests approved for this device class)";
    if (v == "changed") {
        std::string s = "changed within tolerance:";
        for (const auto& i : r.images)
            if (i.changed())
                s += " " + i.image + " max |d| " + num(i.metrics->maxAbs, 3) + ", " +
                     num(100 * i.metrics->overThresholdShare, 3) + "% of pixels over " +
                     num(i.tolerance.pixelThreshold, 3) + ";";
        s.pop_back();
        return s + " (to make it the reference: cavity baselines update --filter '^" + r.id + "$')";
    }
    return "";
}

std::string countsText(const GateRun& run) {
    const auto c = run.counts();
    std::string s;
    for (const char* v : {"fail", "error", "unexpected-pass", "flaky", "known-flake", "expected-fail", "changed", "pass"}) {
        const auto it = c.find(v);
        if (it == c.end()) continue;
        const std::string word = std::string(v) == "pass"      ? "passed unchanged"
                                 : std::string(v) == "fail"    ? "failed"
                                 : std::string(v) == "changed" ? "changed within tolerance"
                                                               : v;
        s += (s.empty() ? "" : ", ") + std::to_string(it->second) + " " + word;
    }
    return s;
}

}  // namespace cavity::report
