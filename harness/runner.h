// Running one configuration on one backend: build the pipeline, measure it,
// read back and write its images. Shared by `cavity run`, `cavity gate` and
// the tests.
#pragma once

#include "pipeline.h"
#include "results.h"

#include <string>

namespace cavity {

struct RunOptions {
    int warmup = 5;
    int frames = 50;
    std::string outDir;               // images go to outDir/<config id>/; empty: none written
    SourceOverrides overrides;        // planted-bug tests
    bool keepImages = false;          // RunRecord::pixels
    bool checkDeterminism = false;    // render once more and compare bit for bit
};

Result<RunRecord> runConfig(gpu::Backend& gpu, const RunConfig& c, const RunOptions& o);

// Checks that `dir` can be created and written without creating anything.
Status checkWritableDir(const std::string& flag, const std::string& dir);

}  // namespace cavity
