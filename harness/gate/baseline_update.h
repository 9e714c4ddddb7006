// Rewriting baseline files all or nothing. `cavity baselines update` stages
// every new file beside the baselines, then commits by renaming a journal
// into place, then moves the files; a kill before the journal leaves the old
// set (the staging folder is dropped by the next command), a kill after it
// leaves a committed update that the next command finishes. Every command
// that reads baselines calls recoverBaselineUpdate first, so none ever sees
// a mix of old and new files.
#pragma once

#include "gate/namespace.h"
#include "result.h"

#include <filesystem>
#include <vector>

namespace cavity::gate {

struct BaselineWrite {
    std::filesystem::path source;   // the new file (a gate output)
    std::filesystem::path target;   // relative to the baselines folder
};

// Finishes a committed update or drops an uncommitted one, and removes the
// ".tmp-" leftovers of the older one-file-at-a-time update.
Status recoverBaselineUpdate(const std::filesystem::path& root);

// Checks every source first (exit 2, nothing changed, if one is missing or
// not a readable file), then stages, commits and applies them.
Status applyBaselineUpdate(const std::filesystem::path& root, const std::vector<BaselineWrite>& writes);

}  // namespace cavity::gate
