#include "compare/compare_verdict.h"

#include "stats/hodges_lehmann.h"
#include "stats/mann_whitney.h"
#include "stats/stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

namespace cavity::compare {

namespace {

double medianOf(const SampleSet& s) { return s.ms.empty() || s.mixedClocks ? NAN : summarize(s.ms).median; }

std::string percent(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%g%%", x);
    return b;
}

// The shift of `after` against `before` in percent of before's median, its
// interval, and the verdict the rules give it at `thresholdPct`.
struct Shift {
    double p = NAN, changePct = NAN, lowPct = NAN, highPct = NAN;
    std::string verdict;   // slower, faster, same
};

Shift shiftOf(const std::vector<double>& before, const std::vector<double>& after, double alpha, double thresholdPct) {
    Shift s;
    const double median = summarize(before).median;
    if (!(median > 0)) return s;
    s.p = stats::mannWhitneyU(before, after).p;
    const auto hl = stats::hodgesLehmann(before, after, alpha);
    s.changePct = 100 * hl.shift / median;
    s.lowPct = 100 * hl.low / median;
    s.highPct = 100 * hl.high / median;
    if (s.p < alpha && s.changePct >= thresholdPct && s.lowPct > 0) s.verdict = "slower";
    else if (s.p < alpha && s.changePct <= -thresholdPct && s.highPct < 0) s.verdict = "faster";
    else s.verdict = "same";
    return s;
}

std::vector<double> cycles(const SampleSet& s) {
    std::vector<double> kcycles(s.ms.size());
    for (size_t i = 0; i < s.ms.size(); ++i) kcycles[i] = s.ms[i] * s.smMhz[i];   // ms x MHz = thousands of cycles
    return kcycles;
}

double medianClock(const SampleSet& s) { return s.smClockKnown() ? summarize(s.smMhz).median : NAN; }

// The SM clock moved between the runs: a pass bound by the SM takes time in
// proportion to 1/clock, so the change must show in cycles as well. Fills
// r's cycles fields where both clocks are known and differ; true where the
// verdict in cycles is not `timeVerdict`.
bool judgeInCycles(CompareRow& r, const SampleSet& before, const SampleSet& after, const CompareThresholds& t,
                   const std::string& timeVerdict) {
    const bool clockDiffers = std::isfinite(r.oldSmMhz) && std::isfinite(r.newSmMhz) &&
                              std::abs(r.newSmMhz - r.oldSmMhz) > kSmClockDiffersPct / 100 * r.oldSmMhz;
    if (!clockDiffers) return false;
    const Shift c = shiftOf(cycles(before), cycles(after), t.alpha, r.thresholdPct);
    r.cyclesVerdict = c.verdict;
    r.cyclesChangePct = c.changePct;
    r.cyclesLowPct = c.lowPct;
    r.cyclesHighPct = c.highPct;
    r.cyclesP = c.p;
    return c.verdict != timeVerdict;
}

const char* const kSoftwareNext =
    "judge speed on a GPU: a software renderer's times are the host CPU's, move with its load, and so may the clock "
    "each run takes";

CompareRow& inconclusive(CompareRow& r, std::string reason, std::string next) {
    r.verdict = "inconclusive";
    r.reason = std::move(reason);
    r.next = std::move(next);
    return r;
}

// Samples so few that even two wholly apart cannot reach alpha would read
// "same" for any change: no verdict (3 against 3 reach only p = 0.1).
bool tooFewSamples(CompareRow& r, const CompareThresholds& t) {
    if (r.nOld >= kMinSamples && r.nNew >= kMinSamples && smallestAttainableP(r.nOld, r.nNew) < t.alpha) return false;
    size_t n = kMinSamples;
    while (smallestAttainableP(n, n) >= t.alpha) ++n;
    char alpha[32];
    std::snprintf(alpha, sizeof alpha, "%g", t.alpha);
    inconclusive(r, "too few samples",
                 "measure at least " + std::to_string(n) + " repetitions a side (fewer cannot reach p < " + alpha + ")");
    return true;
}

}  // namespace

double smallestAttainableP(size_t n, size_t m) {
    // C(n + m, n) built up as a double: exact well past any repetition count used here.
    double ways = 1;
    for (size_t k = 1; k <= std::min(n, m); ++k) ways = ways * double(std::max(n, m) + k) / double(k);
    return std::min(1.0, 2.0 / ways);
}

double smallestStep(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> v(a);
    v.insert(v.end(), b.begin(), b.end());
    std::sort(v.begin(), v.end());
    double step = NAN;
    for (size_t i = 1; i < v.size(); ++i)
        if (v[i] > v[i - 1] && !(v[i] - v[i - 1] >= step)) step = v[i] - v[i - 1];
    return step;
}

namespace {

// The clock both sides have that most of their samples are on ("" where
// they share none).
std::string sharedMajorityClock(const SampleSet& a, const SampleSet& b) {
    std::map<std::string, size_t> count;
    for (const auto* s : {&a, &b})
        for (const auto& c : s->clocks) ++count[c];
    std::string best;
    for (const auto& [c, n] : count) {
        const bool onBoth = std::count(a.clocks.begin(), a.clocks.end(), c) && std::count(b.clocks.begin(), b.clocks.end(), c);
        if (onBoth && (best.empty() || n > count[best])) best = c;
    }
    return best;
}

// Keeps both sides' samples on one clock where a side mixes two and what is
// kept is at least kMixedClockKeepShare of each; false where it is not.
bool keepOneClock(SampleSet& before, SampleSet& after, CompareRow& r) {
    if (!before.mixedClocks && !after.mixedClocks) return true;
    const std::string c = sharedMajorityClock(before, after);
    if (c.empty()) return false;
    SampleSet b = before.onClock(c), a = after.onClock(c);
    if (double(b.ms.size()) < kMixedClockKeepShare * double(before.ms.size()) ||
        double(a.ms.size()) < kMixedClockKeepShare * double(after.ms.size()))
        return false;
    r.leftOutOld = before.ms.size() - b.ms.size();
    r.leftOutNew = after.ms.size() - a.ms.size();
    before = std::move(b);
    after = std::move(a);
    return true;
}

// The counts, clocks and medians of each side there is.
void describeSides(CompareRow& r, const SampleSet* before, const SampleSet* after) {
    if (before) {
        r.nOld = before->ms.size();
        r.oldClock = before->clock;
        r.oldMedianMs = medianOf(*before);
        r.oldSmMhz = medianClock(*before);
    }
    if (after) {
        r.nNew = after->ms.size();
        r.newClock = after->clock;
        r.newMedianMs = medianOf(*after);
        r.newSmMhz = medianClock(*after);
    }
}

}  // namespace

CompareRow compareSeries(const std::string& id, const std::string& pass, const SampleSet* beforeIn,
                         const SampleSet* afterIn, const CompareThresholds& t, bool software) {
    CompareRow r;
    r.id = id;
    r.pass = pass;
    const SampleSet* before = beforeIn;
    const SampleSet* after = afterIn;
    SampleSet kept[2];
    if (before && after) {
        kept[0] = *before;
        kept[1] = *after;
        if (keepOneClock(kept[0], kept[1], r)) {
            before = &kept[0];
            after = &kept[1];
        }
    }
    describeSides(r, before, after);
    if (!before || !after) {
        r.verdict = before ? "gone" : "new";
        return r;
    }
    // A wall-clock time includes submission and the drain around each pass;
    // a timestamp does not. Their difference is the harness, not the change.
    const std::string oneClock = "time both runs on one clock (docs/timing.md), or run them interleaved";
    const bool clocksApart = before->mixedClocks || after->mixedClocks || before->clock != after->clock;
    // A CPU renderer's clock check passes or fails with the host's load, so
    // two runs of one build may take different clocks: that is the host, and
    // its verdict is the software renderer's.
    if (clocksApart && software) return inconclusive(r, "software renderer", kSoftwareNext);
    if (before->mixedClocks || after->mixedClocks) return inconclusive(r, "mixed clocks", oneClock);
    if (before->clock != after->clock) return inconclusive(r, "clocks differ", oneClock);
    if (tooFewSamples(r, t)) return r;

    const auto u = stats::mannWhitneyU(before->ms, after->ms);
    const auto hl = stats::hodgesLehmann(before->ms, after->ms, t.alpha);
    r.p = u.p;
    r.exact = u.exact;
    r.shiftMs = hl.shift;
    r.lowMs = hl.low;
    r.highMs = hl.high;
    r.confidence = hl.confidence;
    // Relative to the old median so that the percentages of every pass read on
    // one scale; an old median of 0 (a pass with no work) has no percentage.
    auto pct = [&](double ms) { return r.oldMedianMs > 0 ? 100.0 * ms / r.oldMedianMs : NAN; };
    r.changePct = pct(hl.shift);
    r.lowPct = pct(hl.low);
    r.highPct = pct(hl.high);
    r.timerStepPct = pct(smallestStep(before->ms, after->ms));
    const double halfWidth = (r.highPct - r.lowPct) / 2;
    r.detectablePct = std::isnan(r.timerStepPct) ? halfWidth : std::max(halfWidth, r.timerStepPct);
    // auto lowers the threshold to what the samples can see, down to the
    // floors (a share of the pass and a time), and never raises it over
    // --min-change: noisier samples than that are inconclusive, not "same"
    // at a wide threshold.
    const double floorPct = std::max(kAutoFloorPct, pct(kAutoFloorMs));
    r.thresholdPct = t.autoMinChange ? std::clamp(std::max(r.detectablePct, floorPct),
                                                  std::min(kAutoFloorPct, t.minChangePct), t.minChangePct)
                                     : t.minChangePct;

    const bool slower = r.p < t.alpha && r.changePct >= r.thresholdPct && r.lowPct > 0;
    const bool faster = r.p < t.alpha && r.changePct <= -r.thresholdPct && r.highPct < 0;
    if (judgeInCycles(r, *before, *after, t, slower ? "slower" : faster ? "faster" : "same") && !software)
        return inconclusive(r, "SM clock differs",
                            "time and cycles (time x SM clock) disagree: lock the SM clock (nvidia-smi "
                            "--lock-gpu-clocks), or run the two builds interleaved (cavity ab)");
    if ((slower || faster) && software) return inconclusive(r, "software renderer", kSoftwareNext);
    if (slower) r.verdict = "slower";
    else if (faster) r.verdict = "faster";
    else if (r.detectablePct > r.thresholdPct)
        return inconclusive(r, "interval too wide",
                            "more repetitions, or the two builds interleaved on one GPU, to see a change of " +
                                percent(r.thresholdPct));
    else r.verdict = "same";
    return r;
}

}  // namespace cavity::compare