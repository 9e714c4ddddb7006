// The build's version: the git commit it was built from (its short hash,
// "-dirty" with uncommitted changes) and the build type. Written at every
// build (cmake/version.cmake), so that what --version prints and what a
// record says made it (results.json, render manifests, the history's
// Cavity version) are one value, not the commit of the last configure.
#pragma once

namespace cavity::measure {

const char* buildCommit();
const char* buildType();

}  // namespace cavity::measure
