// The results database's schema and its migrations. Each migration takes
// the schema from version N to N + 1 inside one transaction with the
// version's update, so a database is at one version or the next, never
// between. A database written by a newer Cavity (a version above ours) is
// refused: we cannot know what its new columns mean, and writing to it
// could leave rows a newer reader misreads.
//
//   runs            one per ingested file and commit: commit, parent, branch,
//                   date (UTC, ISO 8601), device, driver, API, build type,
//                   the Cavity version that measured it, the file's format,
//                   name and digest (the key, with the commit), when ingested
//   configurations  one per configuration id
//   passes          one per (run, configuration, pass, device): API, clock
//                   ("gpu-timestamp" or "wall"), timing mode, software renderer
//   samples         one per repetition (or frame) of a pass: ms, and the SM
//                   and memory clocks in MHz where the file has them
#pragma once

#include "history/database.h"

namespace cavity::history {

// The version this Cavity writes and reads.
constexpr int kSchemaVersion = 2;

// The version the database is at; 0 for an empty one.
Result<int> schemaVersion(Database& db);

// Brings the database to `target` (default: ours), one migration at a time.
// A database above kSchemaVersion: bad input naming it and both versions.
Status migrate(Database& db, int target = kSchemaVersion);

}  // namespace cavity::history
