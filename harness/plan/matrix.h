// baselines/matrices.json: named matrices of configurations, the list both
// `cavity gate` and `cavity_render` run (same entries, same order, same
// shards). No image files here, so that cavity_render can read it on the GPU
// machine.
#pragma once

#include "plan/namespace.h"
#include "core/config.h"

#include <string>
#include <vector>

namespace cavity::plan {

// A baseline key is a configuration id without its API and stage
// ("corner/alchemy/n16/b4/full/160x90"): OpenGL and Vulkan, compute and
// fragment, must all match the same images.
std::string baselineKey(const RunConfig& c);

// The images the gate checks for every configuration, with how their
// baselines are stored.
struct CheckedImage {
    std::string name;        // pipeline image name: "ao", "ao_blur", "color"
    std::string extension;   // ".exr" (half, zip) or ".png" (8-bit, exact)
    bool perceptual;         // also scored with FLIP (LDR colour)
};
const std::vector<CheckedImage>& checkedImages();

// The shape a checked image of a configuration has: the raw AO of a
// half-resolution pipeline is half the size, colour has four channels.
struct ImageShape {
    int width = 0, height = 0, channels = 0;
    bool operator==(const ImageShape&) const = default;
};
ImageShape checkedShape(const RunConfig& c, const std::string& image);
std::string shapeText(const ImageShape& s);   // "160x90x1"

struct MatrixGroup {
    std::vector<std::string> scenes, kernels;   // kernels: names, or {"all"} for every AO kernel
    std::vector<int> samples, blurs;
    // "samples" may be left out for a group of kernels that read no sample
    // count (a package's own, such as a horizon search's directions): each
    // kernel then runs at its default.
    bool samplesGiven = true;
    // Any other kernel parameter, as a list of values ("params": {"radius":
    // [2]}): an axis each, after samples and blur, in name order.
    std::vector<std::pair<std::string, std::vector<double>>> params;
    std::vector<bool> half;
    std::vector<std::pair<int, int>> sizes;
    std::vector<gpu::Api> apis;
    std::vector<gpu::Stage> stages;
};
struct Matrix {
    std::string name;
    // digestText() of the declaration as parsed and dumped again (keys
    // sorted, no whitespace): a render of another matrix, or of this one
    // before an edit (the description included), never matches.
    std::string hash;
    int frames = 3, warmup = 1;
    std::vector<MatrixGroup> groups;
    std::vector<RunConfig> expand() const;   // deduplicated by id, stable order
};
Result<Matrix> loadMatrix(const std::string& path, const std::string& name);

// Shard I of N holds the matrix entries whose index i has i % N == I, as
// GoogleTest's GTEST_TOTAL_SHARDS / GTEST_SHARD_INDEX split tests.
bool inShard(size_t index, int shardIndex, int shardCount);

// The entries of one shard whose id matches `filter` (a regex searched in
// the id; empty: all), each with its index in expand().
struct MatrixEntry {
    size_t index = 0;
    RunConfig config;
};
Result<std::vector<MatrixEntry>> selectEntries(const Matrix& m, int shardIndex, int shardCount,
                                               const std::string& filter);

}  // namespace cavity::plan
