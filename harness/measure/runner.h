// Running one configuration on one backend: build the pipeline, measure it,
// read back and write its images. Shared by `cavity run`, `cavity gate` and
// the tests.
#pragma once

#include "measure/namespace.h"
#include "pipeline/pipeline.h"
#include "measure/results.h"
#include "measure/timing.h"

#include <optional>

#include <string>

namespace cavity::measure {

struct RunOptions {
    int warmup = 5;                   // warm-up frames at least
    int frames = 50;                  // measured frames at least (exactly, with a fixed count)
    // Unset: the device's default (timing.h: batch, stop at the noise target
    // or the time limit on a GPU; a fixed count on a software renderer).
    std::optional<TimingMode> mode;
    std::optional<double> maxNoise;   // relative; 0: a fixed count of frames
    std::optional<double> maxSeconds;
    std::string outDir;               // images go to outDir/<config id>/; empty: none written
    SourceOverrides overrides;        // planted-bug tests
    bool keepImages = false;          // RunRecord::pixels
    bool checkDeterminism = false;    // render once more and compare bit for bit
    // Camera views (the scene's poses 0..views-1) measured in turn, frame f on
    // view f % views, as cavity_bench measures (4): no frame then reads what
    // the frame before left in the caches or wrote to the same images. The
    // images and the record are view 0's. 1: one chain, every frame alike.
    int views = 1;
};

// The timing options runConfig uses on this device.
TimingOptions timingOptions(const gpu::DeviceInfo& device, const RunOptions& o);

Result<RunRecord> runConfig(gpu::Backend& gpu, const RunConfig& c, const RunOptions& o);

// Checks, before any rendering, that `dir` can be created and written, with
// room for paths of `longestInside` characters under it (a configuration id
// and an image name); a probe folder is made and removed, nothing else.
Status checkWritableDir(const std::string& flag, const std::string& dir, size_t longestInside = 160);

// The files a command writes in `dir` at its end: each that exists must be
// a file (or a link to one) it can replace, found before anything is measured.
Status checkOutputFiles(const std::string& flag, const std::string& dir, const std::vector<std::string>& names);
// FILE can be written: not a folder, in a folder that exists and takes a
// new entry. Checked before a command prints or writes anything.
Status checkWritableFile(const std::string& flag, const std::string& file);

}  // namespace cavity::measure