#include "compare/compare_verdict.h"

#include "stats/hodges_lehmann.h"
#include "stats/mann_whitney.h"
#include "stats/stats.h"

#include <cmath>

namespace cavity::compare {

namespace {

double medianOf(const SampleSet& s) { return s.ms.empty() || s.mixedClocks ? NAN : summarize(s.ms).median; }

}  // namespace

CompareRow compareSeries(const std::string& id, const std::string& pass, const SampleSet* before,
                         const SampleSet* after, const CompareThresholds& t) {
    CompareRow r;
    r.id = id;
    r.pass = pass;
    if (before) {
        r.nOld = before->ms.size();
        r.oldClock = before->clock;
        r.oldMedianMs = medianOf(*before);
    }
    if (after) {
        r.nNew = after->ms.size();
        r.newClock = after->clock;
        r.newMedianMs = medianOf(*after);
    }
    if (!before || !after) {
        r.verdict = before ? "gone" : "new";
        return r;
    }
    // A wall-clock time includes submission and the drain around each pass;
    // a timestamp does not. Their difference is the harness, not the change.
    if (before->mixedClocks || after->mixedClocks) {
        r.verdict = "mixed clocks";
        return r;
    }
    if (before->clock != after->clock) {
        r.verdict = "clocks differ";
        return r;
    }

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

    if (r.nOld < kMinSamples || r.nNew < kMinSamples) r.verdict = "too few samples";
    else if (r.p < t.alpha && r.changePct >= t.minChangePct && r.lowPct > 0) r.verdict = "slower";
    else if (r.p < t.alpha && r.changePct <= -t.minChangePct && r.highPct < 0) r.verdict = "faster";
    else r.verdict = "same";
    return r;
}

}  // namespace cavity::compare