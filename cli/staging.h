// Outputs written under a staging folder inside --out and moved to their
// places only once the command has everything: a command that fails or is
// killed leaves what --out held as it was.
#pragma once

#include <filesystem>
#include <string>

namespace cavity::cli {

// --out/.partial-PID, after removing the staging folders whose process is
// gone (a killed command's). The caller creates it.
std::filesystem::path stagingDir(const std::string& out);

// Moves the folder `from` to `to`. A folder already at `to` is exchanged
// with it in one step (renameat2), then removed: a kill between leaves one
// whole folder there, the old or the new, never a mix of the two.
std::error_code replaceFolder(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace cavity::cli
