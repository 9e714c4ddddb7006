// Reading the database back as series over commits: one per (configuration,
// pass, device, clock), since a wall-clock time and a GPU-timestamp time
// measure different things and never share a line. A point is one commit:
// every repetition of every run of that commit pooled, its median and the
// 95% distribution-free interval of that median.
#pragma once

#include "history/database.h"

#include <map>
#include <optional>
#include <regex>

namespace cavity::history {

struct SeriesFilter {
    std::optional<std::regex> id;   // searched in configuration ids
    std::string idText;             // as given, for messages
    std::string pass;               // exact; "" all
    std::string device;             // a part of the device name; "" all
    std::string since, until;       // normalized dates, inclusive; "" open
    // A bound given as a commit: its place in commitOrder, not its date
    // (a commit after its parent may carry an older date). Stored ids.
    std::string sinceCommit, untilCommit;
};

// --since / --until as resolveBound reads them: a date, or a commit.
struct Bound {
    std::string date;     // normalized; "" when a commit was given
    std::string commit;   // the stored id; "" when a date was given
};

struct Point {
    std::string commit, date;       // the commit's first run's date
    std::vector<double> ms;         // every repetition, sorted
    int runs = 0;
    double median = 0, lo = 0, hi = 0;   // the median and its 95% interval
    double min = 0, max = 0;
    bool intervalCoversLess = false;     // too few repetitions for a 95% interval: lo, hi are min, max
};

struct Series {
    std::string configId, pass, device, clock;
    bool softwareRenderer = false;
    std::vector<Point> points;   // in commit order (commitOrder)
    std::string key() const { return configId + " " + pass + " " + device; }
};

Result<std::vector<Series>> loadSeries(Database& db, const SeriesFilter& filter);

// Every commit of the database, oldest first: by the git graph where runs
// name their parent (`ingest --parent`), a commit after its parent, and
// otherwise by its first run's date, then ingest order. A commit stored by
// a short id beside the one full id it begins is one commit, under the
// full id.
Result<std::vector<std::string>> commitOrder(Database& db);
// Each commit's parent (--parent), both in their canonical form, where the
// parent has runs in the database.
Result<std::map<std::string, std::string>> commitParents(Database& db);

// --since / --until: a date (normalizeDate's forms) or a commit (4..40 hex
// digits, a prefix of one run's commit), which bounds by its place in the
// history's order. Bad input for a date that does not parse, a commit the
// database has no run of, or a prefix of two commits.
Result<Bound> resolveBound(Database& db, const std::string& flag, const std::string& value, bool since);

// The 95% interval of a sample's median from order statistics (the
// binomial(n, 1/2) distribution of how many values lie below it): the
// narrowest [x_(k), x_(n+1-k)] that is at least a 95% interval. With fewer
// than 6 values none is: [min, max], and `coversLess` is set.
void medianInterval(const std::vector<double>& sorted, double& lo, double& hi, bool& coversLess);

}  // namespace cavity::history
