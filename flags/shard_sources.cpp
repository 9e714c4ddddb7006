#include "shard_sources.h"

#include "values.h"

#include <cstdlib>
#include <fstream>
#include <vector>

namespace cavity::flags {

namespace {

struct Protocol {
    const char* index;
    const char* total;
};

// Both 0-based. GitLab's CI_NODE_INDEX is 1-based and is not read here: a
// GitLab job passes --shard $((CI_NODE_INDEX - 1))/$CI_NODE_TOTAL (README).
constexpr Protocol kProtocols[] = {{"GTEST_SHARD_INDEX", "GTEST_TOTAL_SHARDS"}, {"TEST_SHARD_INDEX", "TEST_TOTAL_SHARDS"}};

}  // namespace

const char* processEnv(const char* name) { return std::getenv(name); }

Result<Shard> resolveShard(const std::optional<std::string>& flag, const EnvLookup& env) {
    std::vector<Shard> found;
    if (flag) {
        CAVITY_ASSIGN(auto s, parseShard(*flag));
        found.push_back({s.first, s.second, "--shard " + *flag});
    }
    for (const auto& p : kProtocols) {
        const char* i = env(p.index);
        const char* n = env(p.total);
        if (!i && !n) continue;
        if (!i || !n)
            return badInput(std::string(i ? p.index : p.total) + "=" + (i ? i : n) + " is set without " +
                            (i ? p.total : p.index) + ": set both or neither");
        const std::string source = std::string(p.index) + "=" + i + " " + p.total + "=" + n;
        auto s = parseShard(std::string(i) + "/" + n);
        if (!s) return badInput(source + ": must be an index 0 <= I < N and a total N >= 1");
        found.push_back({s->first, s->second, source});
    }
    if (found.empty()) return Shard{};
    for (const auto& s : found)
        if (s.index != found[0].index || s.count != found[0].count)
            return badInput("conflicting shards: " + found[0].source + " but " + s.source + " (set one, or make them agree)");
    return found[0];
}

Status touchShardStatusFiles(const EnvLookup& env) {
    for (const char* name : {"GTEST_SHARD_STATUS_FILE", "TEST_SHARD_STATUS_FILE"}) {
        const char* path = env(name);
        if (!path || !*path) continue;
        std::ofstream f(path, std::ios::app);
        if (!f) return badInput(std::string(name) + "=" + path + ": cannot be created (must be a writable file path)");
    }
    return {};
}

}  // namespace cavity::flags
