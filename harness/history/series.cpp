#include "history/series.h"
#include "history/ingest.h"
#include "history/run_file.h"
#include "stats/stats.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace cavity::history {

void medianInterval(const std::vector<double>& x, double& lo, double& hi, bool& coversLess) {
    const size_t n = x.size();
    lo = n ? x.front() : 0;
    hi = n ? x.back() : 0;
    coversLess = true;
    if (n < 6) return;
    // P(B < k) for B ~ binomial(n, 1/2), summed in logs (n may be thousands of frames).
    size_t k = 0;
    double below = 0;
    for (size_t j = 0; j < n / 2; ++j) {
        below += std::exp(std::lgamma(double(n) + 1) - std::lgamma(double(j) + 1) - std::lgamma(double(n - j) + 1) -
                          double(n) * std::log(2.0));
        if (below > 0.025) break;
        k = j + 1;   // [x_(k), x_(n+1-k)] (1-based) misses with probability 2 P(B < k) <= 0.05
    }
    if (k == 0) return;
    lo = x[k - 1];
    hi = x[n - k];
    coversLess = false;
}

namespace {

struct Key {
    std::string config, pass, device, clock;
    bool operator<(const Key& o) const {
        return std::tie(config, pass, device, clock) < std::tie(o.config, o.pass, o.device, o.clock);
    }
};

void finish(Point& p) {
    std::sort(p.ms.begin(), p.ms.end());
    p.median = percentile(p.ms, 0.5);
    p.min = p.ms.front();
    p.max = p.ms.back();
    medianInterval(p.ms, p.lo, p.hi, p.intervalCoversLess);
}

}  // namespace

Result<std::vector<Series>> loadSeries(Database& db, const SeriesFilter& f) {
    std::string sql =
        "SELECT c.config_id, p.pass, p.device, p.clock, p.software_renderer, r.commit_sha, r.run_date, r.id, s.ms "
        "FROM samples s JOIN passes p ON s.pass_id = p.id JOIN runs r ON p.run_id = r.id "
        "JOIN configurations c ON p.configuration_id = c.id WHERE 1 = 1";
    std::vector<Param> params;
    if (!f.pass.empty()) sql += " AND p.pass = ?", params.push_back(f.pass);
    if (!f.since.empty()) sql += " AND r.run_date >= ?", params.push_back(f.since);
    if (!f.until.empty()) sql += " AND r.run_date <= ?", params.push_back(f.until);
    sql += " ORDER BY c.config_id, p.pass, p.device, p.clock, r.run_date, r.id, s.repetition";
    CAVITY_ASSIGN(const auto rows, db.query(sql, params));
    std::map<Key, Series> byKey;
    std::map<std::pair<Key, std::string>, size_t> pointOf;   // (series, commit) -> index of its point
    std::map<std::pair<Key, std::string>, std::string> lastRun;
    for (const auto& r : rows) {
        const Key k{*r[0], *r[1], *r[2], *r[3]};
        if (f.id && !std::regex_search(k.config, *f.id)) continue;
        if (!f.device.empty() && k.device.find(f.device) == std::string::npos) continue;
        Series& s = byKey[k];
        if (s.configId.empty()) s = {k.config, k.pass, k.device, k.clock, *r[4] != "0", {}};
        const std::string& commit = *r[5];
        auto [it, fresh] = pointOf.emplace(std::make_pair(k, commit), s.points.size());
        if (fresh) s.points.push_back({commit, *r[6], {}, 0});
        Point& p = s.points[it->second];
        if (std::exchange(lastRun[{k, commit}], *r[7]) != *r[7]) ++p.runs;
        p.ms.push_back(std::stod(*r[8]));
    }
    std::vector<Series> out;
    for (auto& [k, s] : byKey) {
        for (auto& p : s.points) finish(p);
        out.push_back(std::move(s));
    }
    return out;
}

Result<std::string> resolveBound(Database& db, const std::string& flag, const std::string& value, bool since) {
    const std::string given = flag + " " + value;
    if (value.empty()) return badInput(flag + " '': must be a date (2026-11-30, 2026-11-30T12:00:00Z) or a commit");
    if (isCommit(value) && value.size() <= 40) {
        CAVITY_ASSIGN(const auto rows, db.query("SELECT commit_sha, min(run_date), max(run_date) FROM runs WHERE commit_sha "
                                                "LIKE ? GROUP BY commit_sha", {value + "%"}));
        if (rows.size() > 1) return badInput(given + ": names " + std::to_string(rows.size()) + " commits (give more digits)");
        if (rows.size() == 1) return *rows[0][since ? 1 : 2];
        if (value.find('-') == std::string::npos)
            return badInput(given + ": no run of that commit in " + db.where() + " (a date or a commit with runs is expected)");
    }
    std::string date = normalizeDate(value);
    if (date.empty()) return badInput(given + ": neither a date (2026-11-30, 2026-11-30T12:00:00Z) nor a commit of 4..40 hex digits");
    // A bare day given as --until takes in the whole day.
    if (!since && value.size() == 10) date = date.substr(0, 10) + "T23:59:59Z";
    return date;
}

}  // namespace cavity::history
