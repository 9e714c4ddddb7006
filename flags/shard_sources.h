// Which shard of a matrix this process runs, from every protocol a CI system
// or test runner speaks: the explicit `--shard I/N`, GoogleTest's
// GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS and Bazel's TEST_SHARD_INDEX /
// TEST_TOTAL_SHARDS (both 0-based). All of them name the same partition
// (matrix.h inShard: entry i is in shard i % N), so a job may set more than
// one, but only if they agree: two sources naming different shards are an
// error, never a silent choice of one.
#pragma once

#include "result.h"

#include <functional>
#include <optional>
#include <string>

namespace cavity::flags {

struct Shard {
    int index = 0, count = 1;
    std::string source;   // what set it ("--shard 1/4", "GTEST_SHARD_INDEX=1 GTEST_TOTAL_SHARDS=4"); empty: the whole matrix
};

using EnvLookup = std::function<const char*(const char*)>;
const char* processEnv(const char* name);   // std::getenv

// `flag`: the value of --shard, if given. A variable of a pair set without
// the other, a value that is not an index below its total, or two sources
// that disagree: a BadInput error naming the variables and their values.
Result<Shard> resolveShard(const std::optional<std::string>& flag, const EnvLookup& env = processEnv);

// GoogleTest and Bazel ask a sharded test to create the file named by
// GTEST_SHARD_STATUS_FILE / TEST_SHARD_STATUS_FILE, to show that it
// understood the sharding variables (Bazel fails a sharded test that does
// not). Touches each one that is set.
Status touchShardStatusFiles(const EnvLookup& env = processEnv);

}  // namespace cavity::flags
