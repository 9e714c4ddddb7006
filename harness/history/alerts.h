// The change points of every series: E-divisive (edivisive.h) over each
// series' per-commit medians. One point per commit, not one per repetition:
// the repetitions of one run share its build, clocks, thermal state and
// machine, so they are not independent draws of what the commit costs.
// Pooled as separate points they would give the t test the small
// within-run variance and many degrees of freedom, and every run-to-run
// wobble would read as a step. Between commits the variance the test sees
// is the one a regression must stand out from. The repetitions still give
// each point its interval (series.h), drawn in the charts.
#pragma once

#include "history/edivisive.h"
#include "history/series.h"

namespace cavity::history {

struct Alert {
    std::string configId, pass, device, clock;
    std::string commit, previousCommit, date;   // the first commit after the step, the last before; its date
    size_t index = 0;                           // of `commit` in its series' points
    double changePct = 0, pValue = 1;           // p adjusted for the splits its segment offered
    double before = 0, after = 0;               // mean of the per-commit medians of the segments either side
    size_t commitsBefore = 0, commitsAfter = 0; // the segments' lengths
    bool provisional = false;                   // too few commits after it yet: held to alpha / 10
    bool newest = false;                        // the series' newest change point: its "after" is the current state
    bool hostClock = false;                     // a software renderer's series: wall time on the host's CPU
    bool slower() const { return changePct > 0; }
};

// Change points of each series, in the series' order (`alerts --since`
// keeps those at or after its bound; the whole series is read to find them).
// With `parents` (commitParents), an alert's previous commit is the
// nearest ancestor of its commit that the series measured, not the point
// before it in the order, which may be another branch's tip: the
// bisect range it prints must run from an ancestor.
std::vector<Alert> findAlerts(const std::vector<Series>& series, const DetectorOptions& options,
                              const std::map<std::string, std::string>* parents = nullptr);

// --fail-on-slower's question: is any series slower now than before its
// newest change point? A slowdown that a later change point undid (a
// revert, a fix) is history, not the current state.
bool slowerNow(const std::vector<Alert>& alerts);

// Change points of one series (the chart marks them).
std::vector<Alert> seriesAlerts(const Series& s, const DetectorOptions& options,
                                const std::map<std::string, std::string>* parents = nullptr);

}  // namespace cavity::history
