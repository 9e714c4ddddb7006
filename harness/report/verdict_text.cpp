#include "core/shell_words.h"
#include "report/verdict_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cavity::report {

namespace {

constexpr double kWorst = 1e300;

int rank(const ConfigResult& r) { return r.fatal() ? 0 : r.verdict() != "pass" ? 1 : 2; }

// How far past a limit `value` is: value / limit for an upper limit, and the
// same for a lower one through its complement (1 - SSIM against 1 - the
// least SSIM allowed, PSNR's limit over the value).
double over(double value, double limit) { return limit > 0 ? value / limit : value > 0 ? kWorst : 0; }

}  // namespace

std::string num(double x, int digits) {
    if (!std::isfinite(x) || x >= 1e299) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.*g", digits, x);
    return b;
}

double severity(const ConfigResult& r) {
    if (!r.error.empty()) return kWorst;
    double worst = 0;
    for (const auto& i : r.images) {
        if (i.route == "negative") return kWorst;
        if (!i.metrics) continue;
        const auto& m = *i.metrics;
        const auto& t = i.tolerance;
        if (m.nonFinite > 0) return kWorst;
        worst = std::max({worst, over(m.maxAbs, t.maxAbs), over(m.meanAbs, t.meanAbs), over(m.rmse, t.rmse),
                          over(m.overThresholdShare, t.overThresholdShare), over(1 - m.ssim, 1 - t.ssimMin),
                          m.flipMean >= 0 ? over(m.flipMean, t.flipMeanMax) : 0.0,
                          m.flipMean >= 0 ? over(m.differingShare, t.differingShareMax) : 0.0,
                          std::isfinite(m.psnr) && m.psnr > 0 ? t.psnrMin / m.psnr : 0.0});
    }
    for (const auto& t : r.timings)
        if (!t.advisory && t.budgetMs) worst = std::max(worst, over(t.medianMs, *t.budgetMs));
    return worst;
}

std::vector<const ConfigResult*> ordered(const GateRun& run) {
    std::vector<const ConfigResult*> v;
    for (const auto& r : run.results) v.push_back(&r);
    std::vector<double> worst(run.results.size());
    for (size_t k = 0; k < worst.size(); ++k) worst[k] = severity(run.results[k]);
    const auto at = [&](const ConfigResult* r) { return worst[size_t(r - run.results.data())]; };
    std::stable_sort(v.begin(), v.end(), [&](auto* a, auto* b) {
        if (rank(*a) != rank(*b)) return rank(*a) < rank(*b);
        if (rank(*a) < 2 && at(a) != at(b)) return at(a) > at(b);
        return a->id < b->id;
    });
    return v;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += (s.empty() ? "" : "; ") + l;
    return s;
}

std::string acceptArgs(const GateRun& run) {
    std::string s = "--from " + (run.out.empty() ? std::string("<gate output>") : core::shellWord(run.out));
    if (!run.baselines.empty()) s += " --baselines " + core::shellWord(run.baselines);
    for (const auto& p : run.packages) s += " --kernels " + core::shellWord(p.folder);
    if (!run.replaced.empty()) s += " --with-kernel-source";
    return s;
}

std::string verdictNote(const ConfigResult& r, const std::string& idPattern, const std::string& accept) {
    const std::string v = r.verdict();
    const std::string args = accept.empty() ? "" : accept + " ";
    const std::string id = idPattern.empty() ? r.id : idPattern;
    if (v == "flaky")
        return "flaky: passed on attempt " + std::to_string(r.attempts) + ", attempt 1 failed: " + joined(r.firstFailures);
    if (v == "expected-fail") return "expected failure (" + r.expectedWhy + ")";
    if (v == "known-flake")
        return "known flake, failed all " + std::to_string(r.attempts) + " attempts (" + r.expectedWhy + ")";
    if (v == "unexpected-pass") return "unexpected pass: listed as an expected failure (" + r.expectedWhy + "); remove the entry";
    // A failure that is the intended result of a change is accepted one
    // configuration at a time, by the command the card prints.
    // Judged against an approved image of its class: a baseline file would
    // not replace that reference, and update refuses; approve is the way.
    const bool byClass = std::any_of(r.images.begin(), r.images.end(),
                                     [](const gate::ImageCheck& i) { return i.baseline.rfind("store:", 0) == 0; });
    if (v == "fail" && r.error.empty() && byClass)
        return "to accept this configuration alone: cavity baselines approve " + args + "--filter '^" + id +
               "$' --why '...' (its digests approved for this device class; it was judged against an approved image "
               "of that class, which a baseline file does not replace)";
    if (v == "fail" && r.error.empty())
        return "to accept this configuration alone: cavity baselines update " + args + "--filter '^" + id +
               "$' (its images become the baselines), or cavity baselines approve " + args + "--filter '^" + id +
               "$' --why '...' (its digests approved for this device class)";
    if (v == "changed") {
        std::string s = "changed within tolerance:";
        for (const auto& i : r.images)
            if (i.changed())
                s += " " + i.image + " max |d| " + num(i.metrics->maxAbs, 3) + ", " +
                     num(100 * i.metrics->overThresholdShare, 3) + "% of pixels over " +
                     num(i.tolerance.pixelThreshold, 3) + ";";
        s.pop_back();
        return s + " (to make it the reference: cavity baselines update " + args + "--filter '^" + id + "$')";
    }
    return "";
}

std::string countsText(const GateRun& run) {
    const auto c = run.counts();
    std::string s;
    for (const char* v : gate::kVerdicts) {
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
