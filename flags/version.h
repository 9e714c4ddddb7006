// The build's version for every program's --version: the git commit it was
// built from (its short hash, "-dirty" with uncommitted changes) and the build
// type, so that a result or a bug report can name the binary that made it.
// Both are written at build time (measure/build_version.h).
#pragma once

#include "measure/build_version.h"

#include <string>

namespace cavity::flags {

inline const char* gitCommit() { return measure::buildCommit(); }
inline const char* buildType() { return measure::buildType(); }

// "cavity 1a2b3c4d5e6f (Release)": what `PROGRAM --version` prints.
inline std::string versionLine(const std::string& program) {
    return program + " " + gitCommit() + " (" + buildType() + ")";
}

}  // namespace cavity::flags
