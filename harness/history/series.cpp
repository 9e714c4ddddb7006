#include "history/series.h"
#include "history/ingest.h"
#include "history/run_file.h"
#include "stats/stats.h"

#include <cstdint>
#include <cctype>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

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

namespace {

struct CommitRow {
    std::string parent, date;
    int64_t firstRun = 0;
};

// The one key of a map by commit id that begins with `prefix`, other than
// `skip`; "" where none or several do. Commit ids are stored as given, a
// short id beside its full one, and every lookup by a short id goes
// through here, so that a prefix of two commits never picks one of them.
template <class Map>
std::string onlyCommitStartingWith(const Map& m, const std::string& prefix, const std::string& skip = "") {
    std::string found;
    for (auto it = m.lower_bound(prefix); it != m.end() && it->first.compare(0, prefix.size(), prefix) == 0; ++it) {
        if (it->first == skip) continue;
        if (!found.empty()) return "";
        found = it->first;
    }
    return found;
}

// A commit stored by a prefix (a short id) stands for the one longer
// commit it begins, where there is exactly one.
std::map<std::string, std::string> canonicalCommits(const std::map<std::string, CommitRow>& commits) {
    std::map<std::string, std::string> out;
    for (const auto& [c, row] : commits) {
        const std::string longer = onlyCommitStartingWith(commits, c, c);
        out[c] = longer.empty() ? c : longer;
    }
    return out;
}

// Each commit in its canonical form (a short id stands for the one full id
// it begins), with its parent resolved to a canonical commit of the
// database ("" where the parent has no run or names two).
Result<std::map<std::string, CommitRow>> mergedCommits(Database& db) {
    CAVITY_ASSIGN(const auto rows, db.query("SELECT commit_sha, parent_sha, min(run_date), min(id) FROM runs "
                                            "GROUP BY commit_sha, parent_sha"));
    std::map<std::string, CommitRow> commits;
    for (const auto& r : rows) {
        CommitRow& c = commits[*r[0]];
        const int64_t id = std::stoll(*r[3]);
        if (c.date.empty() || *r[2] < c.date) c.date = *r[2];
        if (c.firstRun == 0 || id < c.firstRun) c.firstRun = id;
        if (r[1] && c.parent.empty()) c.parent = *r[1];
    }
    const auto canonical = canonicalCommits(commits);
    std::map<std::string, CommitRow> merged;
    for (const auto& [sha, row] : commits) {
        CommitRow& m = merged[canonical.at(sha)];
        if (m.date.empty() || row.date < m.date) m.date = row.date;
        if (m.firstRun == 0 || row.firstRun < m.firstRun) m.firstRun = row.firstRun;
        if (m.parent.empty() && !row.parent.empty()) m.parent = row.parent;
    }
    // A parent named by a prefix of two commits gets no edge.
    for (auto& [sha, row] : merged) {
        if (row.parent.empty() || merged.count(row.parent)) continue;
        row.parent = onlyCommitStartingWith(merged, row.parent);
    }
    for (auto& [sha, row] : merged)
        if (row.parent == sha) row.parent.clear();
    return merged;
}

}  // namespace

Result<std::map<std::string, std::string>> commitParents(Database& db) {
    CAVITY_ASSIGN(const auto merged, mergedCommits(db));
    std::map<std::string, std::string> out;
    for (const auto& [sha, row] : merged)
        if (!row.parent.empty()) out[sha] = row.parent;
    return out;
}

Result<std::vector<std::string>> commitOrder(Database& db) {
    CAVITY_ASSIGN(auto merged, mergedCommits(db));
    // Kahn's algorithm over the parent edges the database knows; among the
    // commits whose parent is placed, the earliest first run goes first
    // (date, then ingest order), which is also the whole order when no run
    // names a parent.
    std::map<std::string, std::vector<std::string>> children;
    std::map<std::string, int> waiting;
    for (const auto& [sha, row] : merged)
        if (!row.parent.empty()) children[row.parent].push_back(sha), ++waiting[sha];
    using Ready = std::tuple<std::string, int64_t, std::string>;
    std::set<Ready> ready;
    for (const auto& [sha, row] : merged)
        if (!waiting[sha]) ready.insert({row.date, row.firstRun, sha});
    std::vector<std::string> order;
    while (order.size() < merged.size()) {
        if (ready.empty()) {
            // A cycle of parents (a database fed wrong ids): the rest by date.
            for (const auto& [sha, row] : merged)
                if (waiting[sha] > 0) ready.insert({row.date, row.firstRun, sha}), waiting[sha] = 0;
        }
        const auto [date, id, sha] = *ready.begin();
        ready.erase(ready.begin());
        if (waiting[sha] < 0) continue;
        waiting[sha] = -1;   // placed
        order.push_back(sha);
        for (const auto& child : children[sha])
            if (waiting[child] > 0 && --waiting[child] == 0) ready.insert({merged[child].date, merged[child].firstRun, child});
    }
    return order;
}

namespace {

// A software renderer's "GPU" timestamps are the host's clock, as its wall
// clock is, and which of the two a run trusted changes from run to run
// (measure/clock_decision.h): one series, on the host's wall clock, so that
// a configuration's history is not split in two.
constexpr const char* kClock = "CASE WHEN p.software_renderer != 0 THEN 'wall' ELSE p.clock END";

// The series the filter selects, in key order, each empty, with
// (configuration row id, pass, device, clock) -> its index.
using SeriesIndex = std::map<std::tuple<std::string, std::string, std::string, std::string>, size_t>;
Result<std::vector<Series>> selectedSeries(Database& db, const SeriesFilter& f, SeriesIndex& seriesOf) {
    std::string keys =
        "SELECT DISTINCT p.configuration_id, c.config_id, p.pass, p.device, " + std::string(kClock) + " FROM passes p "
        "JOIN configurations c ON p.configuration_id = c.id";
    std::vector<Param> keyParams;
    if (!f.pass.empty()) keys += " WHERE p.pass = ?", keyParams.push_back(f.pass);
    CAVITY_ASSIGN(const auto keyRows, db.query(keys, keyParams));
    std::vector<std::pair<Key, std::string>> wanted;
    for (const auto& r : keyRows) {
        const Key k{*r[1], *r[2], *r[3], *r[4]};
        if (f.id && !std::regex_search(k.config, *f.id)) continue;
        // --device h200 finds "NVIDIA H200": a part of the name, in any case.
        const auto lower = [](std::string t) {
            for (char& ch : t) ch = char(std::tolower(static_cast<unsigned char>(ch)));
            return t;
        };
        if (!f.device.empty() && lower(k.device).find(lower(f.device)) == std::string::npos) continue;
        wanted.push_back({k, *r[0]});
    }
    std::sort(wanted.begin(), wanted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Series> out;
    for (const auto& [k, configurationId] : wanted) {
        seriesOf[{configurationId, k.pass, k.device, k.clock}] = out.size();
        out.push_back({k.config, k.pass, k.device, k.clock, false, {}});
    }
    return out;
}

struct RunRow {
    size_t commit;      // its commit's rank in commitOrder
    std::string date;
};

// The runs within --since / --until (dates, or commits' places), by row id.
Result<std::unordered_map<int64_t, RunRow>> selectedRuns(Database& db, const SeriesFilter& f,
                                                         const std::function<size_t(const std::string&)>& rankOf) {
    std::unordered_map<int64_t, RunRow> runs;
    std::string sql = "SELECT id, commit_sha, run_date FROM runs WHERE 1 = 1";
    std::vector<Param> params;
    if (!f.since.empty()) sql += " AND run_date >= ?", params.push_back(f.since);
    if (!f.until.empty()) sql += " AND run_date <= ?", params.push_back(f.until);
    const size_t first = f.sinceCommit.empty() ? 0 : rankOf(f.sinceCommit);
    const size_t last = f.untilCommit.empty() ? SIZE_MAX : rankOf(f.untilCommit);
    CAVITY_TRY(db.forEach(sql, params, [&](const Row& r) -> Status {
        const size_t rank = rankOf(*r[1]);
        if (rank >= first && rank <= last) runs[std::stoll(*r[0])] = {rank, *r[2]};
        return {};
    }));
    return runs;
}

// Each series' points in commit order.
void orderPoints(std::vector<Series>& series, const std::vector<std::unordered_map<size_t, size_t>>& pointOf) {
    for (size_t i = 0; i < series.size(); ++i) {
        Series& s = series[i];
        for (auto& p : s.points) finish(p);
        std::vector<std::pair<size_t, size_t>> byRank(pointOf[i].begin(), pointOf[i].end());   // (commit rank, point)
        std::sort(byRank.begin(), byRank.end());
        std::vector<Point> ordered;
        ordered.reserve(s.points.size());
        for (const auto& [commit, point] : byRank) ordered.push_back(std::move(s.points[point]));
        s.points = std::move(ordered);
    }
    series.erase(std::remove_if(series.begin(), series.end(), [](const Series& s) { return s.points.empty(); }), series.end());
}

}  // namespace

Result<std::vector<Series>> loadSeries(Database& db, const SeriesFilter& f) {
    // Four reads, each streamed: the series (few), the runs (one a file),
    // the passes (one a run and series) and the samples. Only what the
    // series are made of is kept: a median per commit needs its samples,
    // but no row is held, so memory follows the samples' count, not the
    // rows' text. One scan of the samples in storage order, rather than
    // a query per series, reads each page of the database once.
    SeriesIndex seriesOf;
    CAVITY_ASSIGN(std::vector<Series> out, selectedSeries(db, f, seriesOf));
    if (out.empty()) return out;
    CAVITY_ASSIGN(const auto order, commitOrder(db));
    std::map<std::string, size_t> rank;
    for (size_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
    // Each stored form of a commit (a short id beside its full one) to its canonical form's rank.
    const auto rankOf = [&](const std::string& sha) -> size_t {
        const std::string c = rank.count(sha) ? sha : onlyCommitStartingWith(rank, sha);
        return c.empty() ? order.size() : rank.at(c);
    };
    CAVITY_ASSIGN(const auto runs, selectedRuns(db, f, rankOf));
    // A pass row to its series and run.
    std::unordered_map<int64_t, std::pair<uint32_t, int64_t>> passes;
    std::string sql = "SELECT id, configuration_id, pass, device, " + std::string(kClock) + ", software_renderer, run_id FROM passes p";
    std::vector<Param> params;
    if (!f.pass.empty()) sql += " WHERE pass = ?", params.push_back(f.pass);
    CAVITY_TRY(db.forEach(sql, params, [&](const Row& r) -> Status {
        const auto it = seriesOf.find({*r[1], *r[2], *r[3], *r[4]});
        const int64_t run = std::stoll(*r[6]);
        if (it == seriesOf.end() || !runs.count(run)) return {};   // another series, or outside --since / --until
        if (*r[5] != "0") out[it->second].softwareRenderer = true;
        passes[std::stoll(*r[0])] = {uint32_t(it->second), run};
        return {};
    }));
    std::vector<std::unordered_map<size_t, size_t>> pointOf(out.size());   // per series: commit rank -> point
    std::vector<std::unordered_map<size_t, int64_t>> lastRun(out.size());
    CAVITY_TRY(db.forEach("SELECT pass_id, ms FROM samples", {}, [&](const Row& r) -> Status {
        const auto it = passes.find(std::stoll(*r[0]));
        if (it == passes.end()) return {};
        const auto [series, runId] = it->second;
        Series& s = out[series];
        const RunRow& run = runs.at(runId);
        auto [at, fresh] = pointOf[series].emplace(run.commit, s.points.size());
        if (fresh) s.points.push_back({run.commit < order.size() ? order[run.commit] : "", run.date, {}, 0});
        Point& p = s.points[at->second];
        if (run.date < p.date) p.date = run.date;   // the commit's first run
        auto& last = lastRun[series][run.commit];
        if (last != runId) ++p.runs, last = runId;
        p.ms.push_back(std::stod(*r[1]));
        return {};
    }));
    orderPoints(out, pointOf);
    return out;
}

Result<Bound> resolveBound(Database& db, const std::string& flag, const std::string& value, bool since) {
    const std::string given = flag + " " + value;
    if (value.empty()) return badInput(flag + " '': must be a date (2026-11-30, 2026-11-30T12:00:00Z) or a commit");
    if (isCommit(value)) {
        CAVITY_ASSIGN(const auto rows, db.query("SELECT DISTINCT commit_sha FROM runs WHERE commit_sha LIKE ?", {value + "%"}));
        if (rows.size() > 1) return badInput(given + ": names " + std::to_string(rows.size()) + " commits (give more digits)");
        if (rows.size() == 1) return Bound{"", *rows[0][0]};
        if (value.find('-') == std::string::npos)
            return badInput(given + ": no run of that commit in " + db.where() + " (a date or a commit with runs is expected)");
    }
    std::string date = normalizeDate(value);
    if (date.empty()) return badInput(given + ": neither a date (2026-11-30, 2026-11-30T12:00:00Z) nor a commit of 4..64 hex digits");
    // A bare day given as --until takes in the whole day.
    if (!since && value.size() == 10) date = date.substr(0, 10) + "T23:59:59Z";
    return Bound{date, ""};
}

}  // namespace cavity::history
