#include "history/alerts.h"

#include <set>

namespace cavity::history {

namespace {

// The nearest ancestor of points[index] among points[0..index), walking the
// parent links; "" where the links do not reach one.
std::string measuredAncestor(const Series& s, size_t index, const std::map<std::string, std::string>& parents) {
    std::set<std::string> before;
    for (size_t i = 0; i < index; ++i) before.insert(s.points[i].commit);
    std::set<std::string> seen;
    for (auto it = parents.find(s.points[index].commit); it != parents.end() && seen.insert(it->second).second;
         it = parents.find(it->second))
        if (before.count(it->second)) return it->second;
    return "";
}

}  // namespace

std::vector<Alert> seriesAlerts(const Series& s, const DetectorOptions& options,
                                const std::map<std::string, std::string>* parents) {
    std::vector<double> medians;
    for (const auto& p : s.points) medians.push_back(p.median);
    std::vector<Alert> out;
    const auto points = detectChangePoints(medians, options);
    for (const auto& c : points) {
        Alert a;
        a.configId = s.configId;
        a.pass = s.pass;
        a.device = s.device;
        a.clock = s.clock;
        a.index = c.index;
        a.commit = s.points[c.index].commit;
        a.date = s.points[c.index].date;
        a.previousCommit = s.points[c.index - 1].commit;
        if (parents)
            if (const std::string ancestor = measuredAncestor(s, c.index, *parents); !ancestor.empty())
                a.previousCommit = ancestor;
        a.changePct = c.change() * 100;
        a.pValue = c.pValue;
        a.before = c.meanBefore;
        a.after = c.meanAfter;
        a.commitsBefore = c.pointsBefore;
        a.commitsAfter = c.pointsAfter;
        a.provisional = c.provisional;
        a.newest = &c == &points.back();
        a.hostClock = s.softwareRenderer || s.clock == "wall";
        out.push_back(std::move(a));
    }
    return out;
}

std::vector<Alert> findAlerts(const std::vector<Series>& series, const DetectorOptions& options,
                              const std::map<std::string, std::string>* parents) {
    std::vector<Alert> out;
    for (const auto& s : series)
        for (auto& a : seriesAlerts(s, options, parents)) out.push_back(std::move(a));
    return out;
}

bool slowerNow(const std::vector<Alert>& alerts) {
    for (const auto& a : alerts)
        if (a.newest && a.slower()) return true;
    return false;
}

}  // namespace cavity::history
