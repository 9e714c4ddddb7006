// `cavity history`: its subcommands and the flags they share (the filters,
// the detector's parameters), split over history_command.cpp (the
// dispatch, ingest) and history_views.cpp (show, chart, alerts).
#pragma once

#include "cli.h"
#include "history/alerts.h"
#include "history/database.h"

#include <memory>

namespace cavity::cli {

int historyIngest(const std::vector<std::string>& argv);
int historyShow(const std::vector<std::string>& argv);
int historyChart(const std::vector<std::string>& argv);
int historyAlerts(const std::vector<std::string>& argv);

// The flags the read commands share.
FlagSpec historyDbFlag();
std::vector<FlagSpec> historyFilterFlags(bool until);
std::vector<FlagSpec> historyDetectorFlags();

// What the read commands were given: the database, the filters (dates and
// commits resolved against it) and the detector's parameters.
struct HistoryQuery {
    std::unique_ptr<history::Database> db;
    history::SeriesFilter filter;
    history::DetectorOptions detector;
    history::Bound since;   // --since resolved (the alerts' bound)
};

// Reads the shared flags from `parsed` (others are left to the caller),
// opens the database (never creating it) and resolves --since and --until.
Result<HistoryQuery> historyQuery(const ParsedFlags& parsed);

// The series that match, or bad input naming the filters when none does.
Result<std::vector<history::Series>> matchingSeries(HistoryQuery& q);

}  // namespace cavity::cli
