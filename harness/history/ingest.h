// Storing a run file in the results database: one run row per (file
// content, commit), its configurations, passes and every sample, all in one
// transaction, so a kill or an error halfway leaves nothing of the file.
#pragma once

#include "history/database.h"
#include "history/run_file.h"

namespace cavity::history {

struct RunInfo {
    std::string commit;      // hex, 4..64 digits (the caller checks)
    std::string parent;      // "" when not given
    std::string branch;      // "" when not given
    std::string date;        // normalized (normalizeDate); "" takes the file's own, else now
    std::string buildType;   // "" when not given
};

struct Ingested {
    int64_t runId = 0;
    bool alreadyThere = false;   // the same content was ingested for this commit before: no run written
    bool renamed = false;        // a short id stored before now reads as the full id given
    size_t passes = 0, samples = 0;
    std::string commit;           // as stored: a short id given for a full one stored reads as that one
};

Result<Ingested> ingest(Database& db, const RunFile& file, const RunInfo& info);

// A commit as git names one: 4 to 64 hex digits.
bool isCommit(const std::string& s);

}  // namespace cavity::history
