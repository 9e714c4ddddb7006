#include "history/alerts.h"

namespace cavity::history {

std::vector<Alert> seriesAlerts(const Series& s, const DetectorOptions& options) {
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

std::vector<Alert> findAlerts(const std::vector<Series>& series, const DetectorOptions& options) {
    std::vector<Alert> out;
    for (const auto& s : series)
        for (auto& a : seriesAlerts(s, options)) out.push_back(std::move(a));
    return out;
}

bool slowerNow(const std::vector<Alert>& alerts) {
    for (const auto& a : alerts)
        if (a.newest && a.slower()) return true;
    return false;
}

}  // namespace cavity::history
