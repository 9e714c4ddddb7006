// The build's version for every program's --version: the git commit it was
// built from (its short hash, "-dirty" with uncommitted changes) and the build
// type, so that a result or a bug report can name the binary that made it.
// gitCommit() and buildType() are written at build time (cmake/version.cmake).
#pragma once

#include <string>

namespace cavity::flags {

const char* gitCommit();
const char* buildType();

// "cavity 1a2b3c4d5e6f (Release)": what `PROGRAM --version` prints.
inline std::string versionLine(const std::string& program) {
    return program + " " + gitCommit() + " (" + buildType() + ")";
}

}  // namespace cavity::flags
