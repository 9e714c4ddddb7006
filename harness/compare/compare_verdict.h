// One row of `cavity compare`: a configuration's pass in two runs, the
// numbers, and a verdict a pull request can gate on. "slower" needs three
// things at once: the U test says the two samples differ (p < alpha), the
// estimated shift is large enough to matter (>= min-change percent of the old
// median), and the interval of the shift lies wholly above zero. GPU
// timestamps are steady enough that the test alone flags a move far too
// small to matter (the measurement notebook has one, with 5 repetitions a
// side); the size alone flags noise when samples are few; the interval keeps
// the estimate honest when the test and the shift disagree on a skewed sample.
#pragma once

#include "compare/namespace.h"
#include "compare/sample_sets.h"

#include <cmath>
#include <string>

namespace cavity::compare {

struct CompareThresholds {
    double alpha = 0.05;       // significance of the U test; the interval is at 1 - alpha
    double minChangePct = 2;   // smallest shift, in percent of the old median, worth a verdict
    // --min-change auto: each pass's threshold is its detectable change
    // (below), never under kAutoFloorPct or kAutoFloorMs nor over
    // minChangePct: noisier samples are inconclusive.
    bool autoMinChange = false;
};

// The floor of --min-change auto: two unchanged runs of one build, one after
// the other on an H200, moved untouched passes by just under this much with
// p < 0.05 (study 2026-12-01_h200_verdict); a change the drift between two
// processes can make is not called.
constexpr double kAutoFloorPct = 0.5;

// And never under this much time, in ms: separate processes of one build
// move a short pass by a fixed amount the repetitions inside either process
// cannot see. On the H200 two unchanged processes one after the other moved
// the shortest passes by up to two steps of GL's timer (less on Vulkan), far
// more than the intervals inside each process allow for, and this floor is
// just over that move (study 2026-12-03_h200_sensitivity). It is a
// negligible share of an AO pass and a noticeable one of a short blur.
constexpr double kAutoFloorMs = 0.0003;

// A side whose samples come from two clocks (a repetition whose warm clock
// check failed and moved to the wall clock) is judged on the clock most of
// both sides' samples share, leaving the others out, when that keeps at
// least this share of each side; otherwise it has no verdict. On the H200 a
// single repetition that moved (study 2026-12-03_h200_sensitivity2) took its
// configuration's verdict with it in every pass.
constexpr double kMixedClockKeepShare = 0.75;

// Fewer samples than this on a side gives no verdict: with 2 against 2 the
// smallest two-sided p the U test can give is 1/3.
constexpr size_t kMinSamples = 3;

// The smallest two-sided p the exact U test can give n against m samples
// (the two samples wholly apart, no ties): 2 / C(n + m, n). 3 against 3 give
// 0.1, 4 against 4 0.029: below alpha, a change can be called at all.
double smallestAttainableP(size_t n, size_t m);

struct CompareRow {
    std::string id, pass;
    // slower, faster, same, inconclusive, new, gone
    std::string verdict;
    // inconclusive: why ("too few samples", "mixed clocks", "clocks differ",
    // "interval too wide", "software renderer") and what to do next.
    std::string reason, next;
    // The smallest change these two samples could have called, in percent of
    // the old median: the larger of the interval's half-width and the
    // timer's step (the smallest difference between two distinct samples).
    double detectablePct = NAN, timerStepPct = NAN;
    double thresholdPct = NAN;   // the change a verdict needed: --min-change, or auto's
    size_t nOld = 0, nNew = 0;          // the samples judged
    size_t leftOutOld = 0, leftOutNew = 0;   // samples on another clock, left out (kMixedClockKeepShare)
    std::string oldClock, newClock;   // "" where the side is missing
    // NaN where not computed: medians of a missing or mixed-clock side; the
    // rest only when both sides are on one clock.
    double oldMedianMs = NAN, newMedianMs = NAN;
    double shiftMs = NAN, lowMs = NAN, highMs = NAN;           // Hodges-Lehmann shift and interval
    double changePct = NAN, lowPct = NAN, highPct = NAN;       // the same in percent of the old median
    double confidence = NAN;   // the coverage the interval has (see ShiftEstimate)
    double p = NAN;
    bool exact = false;        // exact U distribution for p and interval
    // The SM clocks the two sides ran at (medians over their samples, from
    // NVML); NaN where a file records none. Where both are known and differ
    // by more than kSmClockDiffersPct, the change is judged in cycles too
    // (each sample's time x its clock), as nvbench's robust compare does: a
    // verdict stands only where time and cycles agree.
    double oldSmMhz = NAN, newSmMhz = NAN;
    std::string cyclesVerdict;   // slower, faster, same; "" where not judged in cycles
    double cyclesChangePct = NAN, cyclesLowPct = NAN, cyclesHighPct = NAN, cyclesP = NAN;
};

// Two runs whose median SM clocks differ by more than this, in percent, are
// judged in cycles as well. NVML reads the clock in 15 MHz steps on Hopper,
// a smaller share of its working clock than this, so one step is not a
// difference.
constexpr double kSmClockDiffersPct = 1.0;

// Either side may be null: the pass is new or gone. `software`: either run
// was on a software renderer (llvmpipe, lavapipe), whose times are the host
// CPU's: no change is called slower or faster there.
CompareRow compareSeries(const std::string& id, const std::string& pass, const SampleSet* before,
                         const SampleSet* after, const CompareThresholds& t, bool software = false);

// The smallest positive difference between two distinct values of a and b
// together (a timer's step, where the samples are on one); NaN with fewer
// than two distinct values.
double smallestStep(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace cavity::compare