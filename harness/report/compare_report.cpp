#include "report/compare_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace cavity::report {

using nlohmann::json;

namespace {

// The verdicts in the order a summary lists them.
constexpr std::array<const char*, 6> kVerdicts = {"slower", "faster", "same", "inconclusive", "new", "gone"};

std::string format(const char* f, double v) {
    if (std::isnan(v)) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// Small p-values in scientific notation: 0.0000 would hide how small.
std::string formatP(double p) { return std::isnan(p) ? "-" : format(p >= 1e-3 ? "%.4f" : "%.1e", p); }

std::string formatInterval(double low, double high) {
    if (std::isnan(low) || std::isnan(high)) return "-";
    std::string s = "[";
    s += format("%+.1f%%", low);
    s += ", ";
    s += format("%+.1f%%", high);
    return s + "]";
}

std::string confidenceLabel(double alpha) { return format("%g", 100 * (1 - alpha)) + "%"; }

std::string describe(const SampleSets& s) {
    std::set<std::string> ids;
    for (const auto& [key, series] : s.series) ids.insert(key.first);
    std::string text = s.path + " (" + (s.format == "google-benchmark" ? "Google Benchmark JSON" : "cavity results.json") +
                       ", " + std::to_string(ids.size()) + " configuration" + (ids.size() == 1 ? "" : "s");
    std::string skipped;
    if (s.skippedErrors)
        skipped += std::to_string(s.skippedErrors) + " errored entr" + (s.skippedErrors == 1 ? "y" : "ies");
    if (s.skippedMirrors)
        skipped += (skipped.empty() ? "" : ", ") + std::to_string(s.skippedMirrors) + " per-pass @ entr" +
                   (s.skippedMirrors == 1 ? "y" : "ies");
    return text + (skipped.empty() ? "" : "; skipped " + skipped) + ")";
}

json number(double v) { return std::isnan(v) ? json() : json(v); }
json text(const std::string& s) { return s.empty() ? json() : json(s); }

json side(const SampleSets& s) {
    return {{"file", s.path}, {"format", s.format}, {"skipped_errors", s.skippedErrors},
            {"skipped_mirrors", s.skippedMirrors}};
}

std::map<std::string, int> tally(const std::vector<CompareRow>& rows) {
    std::map<std::string, int> counts;
    for (const char* v : kVerdicts) counts[v] = 0;
    for (const auto& r : rows) ++counts[r.verdict];
    return counts;
}

}  // namespace

std::vector<CompareRow> compareAll(const SampleSets& before, const SampleSets& after, const CompareThresholds& t) {
    std::vector<std::pair<std::string, std::string>> keys = before.order;
    for (const auto& k : after.order)
        if (!before.series.count(k)) keys.push_back(k);
    // Keep a configuration's rows together, each group where its id first appears.
    std::map<std::string, size_t> rank;
    for (const auto& k : keys) rank.emplace(k.first, rank.size());
    std::stable_sort(keys.begin(), keys.end(),
                     [&](const auto& l, const auto& r) { return rank.at(l.first) < rank.at(r.first); });
    std::vector<CompareRow> rows;
    for (const auto& k : keys) {
        const auto o = before.series.find(k), n = after.series.find(k);
        rows.push_back(compareSeries(k.first, k.second, o == before.series.end() ? nullptr : &o->second,
                                     n == after.series.end() ? nullptr : &n->second, t,
                                     before.softwareRenderer || after.softwareRenderer));
    }
    return rows;
}

std::string compareTable(const std::vector<CompareRow>& rows, const SampleSets& before, const SampleSets& after,
                         const CompareThresholds& t) {
    const std::string level = confidenceLabel(t.alpha);
    // The change in cycles, only where some row's SM clock differed between the runs.
    const bool anyCycles = std::any_of(rows.begin(), rows.end(), [](const CompareRow& r) { return !r.cyclesVerdict.empty(); });
    std::vector<std::vector<std::string>> cells = {
        {"configuration", "pass", "old ms", "new ms", "change", level + " interval", "detectable", "p", "n old/new"}};
    if (anyCycles) cells[0].push_back("SM MHz old/new: cycles");
    cells[0].push_back("verdict");
    for (const auto& r : rows) {
        cells.push_back({r.id, r.pass, format("%.4f", r.oldMedianMs), format("%.4f", r.newMedianMs),
                         format("%+.1f%%", r.changePct), formatInterval(r.lowPct, r.highPct),
                         format("%.2f%%", r.detectablePct), formatP(r.p),
                         std::to_string(r.nOld) + "/" + std::to_string(r.nNew)});
        if (anyCycles)
            cells.back().push_back(r.cyclesVerdict.empty() ? "-"
                                                           : format("%.0f", r.oldSmMhz) + "/" + format("%.0f", r.newSmMhz) +
                                                                 ": " + format("%+.1f%%", r.cyclesChangePct) + " " +
                                                                 r.cyclesVerdict);
        cells.back().push_back(r.verdict + (r.reason.empty() ? "" : ": " + r.reason));
    }
    std::vector<size_t> width(cells[0].size(), 0);
    for (const auto& row : cells)
        for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    // Names and the verdict read from the left, numbers line up on the right.
    const size_t verdictColumn = cells[0].size() - 1;
    auto leftAligned = [&](size_t c) { return c < 2 || c == verdictColumn; };
    std::string out = "old: " + describe(before) + "\nnew: " + describe(after) + "\n\n";
    for (const auto& row : cells) {
        std::string line;
        for (size_t c = 0; c < row.size(); ++c) {
            const std::string pad(width[c] - row[c].size(), ' ');
            line += (c ? "  " : "") + (leftAligned(c) ? row[c] + (c + 1 < row.size() ? pad : "") : pad + row[c]);
        }
        out += line + "\n";
    }
    const auto counts = tally(rows);
    std::string summary;
    for (const char* v : kVerdicts)
        if (counts.at(v) || std::string(v) == "slower" || std::string(v) == "faster" || std::string(v) == "same")
            summary += (summary.empty() ? "" : ", ") + std::to_string(counts.at(v)) + " " + v;
    out += "\n" + summary + "\n";
    out += "slower/faster: U-test p < " + format("%g", t.alpha) + ", change >= " +
           (t.autoMinChange ? "each pass's detectable change (at least " + format("%g", kAutoFloorPct) + "% and " +
                                  format("%g", kAutoFloorMs * 1000) + " us, at most " + format("%g", t.minChangePct) + "%)"
                            : format("%g", t.minChangePct) + "%") +
           " of the old median and the " + level + " interval of the change excludes 0; detectable: the smallest "
           "change these samples could call (the interval's half-width, or the timer's step)\n";
    size_t judgedOnOne = 0, leftOut = 0;
    for (const auto& r : rows)
        if (r.leftOutOld + r.leftOutNew) {
            ++judgedOnOne;
            leftOut += r.leftOutOld + r.leftOutNew;
        }
    if (judgedOnOne)
        out += std::to_string(judgedOnOne) + " rows judged on the clock most of their samples share, " +
               std::to_string(leftOut) + " samples on another clock left out (left_out_old/new in --json)\n";
    // Each reason for an inconclusive row once, with what to do about it.
    std::map<std::string, std::pair<int, std::string>> reasons;
    for (const auto& r : rows)
        if (!r.reason.empty()) {
            ++reasons[r.reason].first;
            reasons[r.reason].second = r.next;
        }
    for (const auto& [reason, n] : reasons)
        out += "inconclusive, " + reason + " (" + std::to_string(n.first) + "): " + n.second + "\n";
    return out;
}

json compareJson(const std::vector<CompareRow>& rows, const SampleSets& before, const SampleSets& after,
                 const CompareThresholds& t) {
    json list = json::array();
    for (const auto& r : rows)
        list.push_back({{"id", r.id},
                        {"pass", r.pass},
                        {"verdict", r.verdict},
                        {"reason", text(r.reason)},
                        {"next", text(r.next)},
                        {"detectable_pct", number(r.detectablePct)},
                        {"timer_step_pct", number(r.timerStepPct)},
                        {"threshold_pct", number(r.thresholdPct)},
                        {"n_old", r.nOld},
                        {"n_new", r.nNew},
                        {"left_out_old", r.leftOutOld},
                        {"left_out_new", r.leftOutNew},
                        {"old_clock", text(r.oldClock)},
                        {"new_clock", text(r.newClock)},
                        {"old_median_ms", number(r.oldMedianMs)},
                        {"new_median_ms", number(r.newMedianMs)},
                        {"shift_ms", number(r.shiftMs)},
                        {"ci_low_ms", number(r.lowMs)},
                        {"ci_high_ms", number(r.highMs)},
                        {"change_pct", number(r.changePct)},
                        {"ci_low_pct", number(r.lowPct)},
                        {"ci_high_pct", number(r.highPct)},
                        {"ci_coverage", number(r.confidence)},
                        {"p", number(r.p)},
                        {"method", std::isnan(r.p) ? json() : json(r.exact ? "exact" : "asymptotic")},
                        {"old_sm_mhz", number(r.oldSmMhz)},
                        {"new_sm_mhz", number(r.newSmMhz)},
                        {"cycles_verdict", text(r.cyclesVerdict)},
                        {"cycles_change_pct", number(r.cyclesChangePct)},
                        {"cycles_ci_low_pct", number(r.cyclesLowPct)},
                        {"cycles_ci_high_pct", number(r.cyclesHighPct)},
                        {"cycles_p", number(r.cyclesP)}});
    return {{"schema", kCompareSchema},
            {"old", side(before)},
            {"new", side(after)},
            {"alpha", t.alpha},
            {"confidence", 1 - t.alpha},
            {"min_change_pct", t.autoMinChange ? json("auto") : json(t.minChangePct)},
            {"counts", tally(rows)},
            {"rows", list}};
}

}  // namespace cavity::report