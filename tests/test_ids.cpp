// Configuration ids (harness/core/config.cpp configId): distinct configurations
// never share one, ids at the defaults read as they always did (baseline
// paths depend on it), and every kernel parameter sweeps in cavity run.
#include "core/config.h"
#include "pipeline/config_id.h"
#include "plan/matrix.h"
#include "pipeline/pipeline.h"
#include "run_binary.h"
#include "plan/sweep.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace fs = std::filesystem;
using namespace cavity;
using namespace cavity::harness;

namespace {

// What a configuration runs, independent of its id: every pass's kernel with
// the values it would read, and the fields that are not parameters.
std::string contentKey(const RunConfig& c) {
    std::string key = c.kernel + "|" + c.gbufferSource() + "|" + c.gbufferFile + "|" + std::to_string(c.width) + "x" +
                      std::to_string(c.height) + "|" + (c.half ? "half" : "full") + "|" + gpu::apiName(c.api) + "|" +
                      std::to_string(int(c.stage));
    std::set<std::string> read;
    for (const auto& spec : buildPasses(c)) {
        const auto* k = kernels::find(spec.kernel);
        key += "|" + spec.name + ":" + spec.kernel;
        if (!k) continue;
        for (const auto& [name, v] : kernels::withDefaults(*k, c.params)) {
            key += "," + name + "=" + std::to_string(v);
            read.insert(name);
        }
    }
    // A parameter no pass reads is still part of what was asked.
    for (const auto& [name, v] : c.params)
        if (!read.count(name)) key += ";" + name + "=" + std::to_string(v);
    return key;
}

// Every pair of configurations: same id exactly when the same content.
void expectIdsMatchContent(const std::vector<RunConfig>& configs) {
    std::map<std::string, std::string> keyOfId, idOfKey;
    for (const auto& c : configs) {
        const std::string id = configId(c), key = contentKey(c);
        auto [it, fresh] = keyOfId.emplace(id, key);
        EXPECT_TRUE(fresh || it->second == key) << id << " names two configurations";
        auto [jt, fresh2] = idOfKey.emplace(key, id);
        EXPECT_TRUE(fresh2 || jt->second == id) << "one configuration has ids " << jt->second << " and " << id;
    }
}

RunConfig with(std::initializer_list<std::pair<const char*, const char*>> params, const std::string& kernel = "alchemy") {
    RunConfig c;
    c.kernel = kernel;
    for (const auto& [n, v] : params) EXPECT_TRUE(setParam(c, n, v).ok()) << n << " " << v;
    return c;
}

}  // namespace

TEST(ConfigId, DefaultsKeepTheirShortId) {
    EXPECT_EQ(configId(with({})), "corner/alchemy/n16/b4/full/320x180/vk/compute");
    // Given at its default, a parameter changes nothing and says nothing.
    EXPECT_EQ(configId(with({{"radius", "0.5"}, {"bias", "0.01"}})), "corner/alchemy/n16/b4/full/320x180/vk/compute");
}

TEST(ConfigId, NamesEveryParameterThatDiffersFromItsDefault) {
    EXPECT_EQ(configId(with({{"radius", "0.3"}})), "corner/alchemy/n16/b4/radius=0.3/full/320x180/vk/compute");
    EXPECT_EQ(configId(with({{"radius", "0.3"}, {"bias", "0.02"}})),
              "corner/alchemy/n16/b4/bias=0.02/radius=0.3/full/320x180/vk/compute");
    EXPECT_NE(configId(with({{"radius", "0.3"}})), configId(with({{"radius", "1"}})));
    // Every declared numeric parameter of every AO kernel, moved off its default, changes the id.
    for (const auto& k : kernels::all()) {
        if (k.role != cavity::kernels::Role::Ao && k.role != cavity::kernels::Role::Reference) continue;
        RunConfig base;
        base.kernel = k.name;
        for (const auto& u : k.params) {
            const auto& p = *u.decl;
            if (p.type == kernels::ParamType::Enum) continue;
            RunConfig c = base;
            c.params[p.name] = u.def == p.max ? p.min + (p.minExclusive ? (p.max - p.min) / 2 : 0) : p.max;
            EXPECT_NE(configId(c), configId(base)) << k.name << " --" << p.name;
        }
    }
}

TEST(ConfigId, GroundTruthNamesItsRays) {
    RunConfig c = with({}, "ground_truth");
    EXPECT_EQ(configId(c), "corner/ground_truth/rays1024/b4/full/320x180/vk/compute");
    ASSERT_TRUE(setParam(c, "rays", "2048").ok());
    EXPECT_EQ(configId(c), "corner/ground_truth/rays2048/b4/full/320x180/vk/compute");
}

// A matrix names an enum's values by choice, as the command line does, or
// by index; anything else is refused naming the choices.
TEST(ConfigId, MatrixEnumValuesByName) {
    const fs::path dir = fs::temp_directory_path() / "cavity_matrix_enum";
    fs::create_directories(dir);
    const std::string path = (dir / "matrices.json").string();
    auto write = [&](const std::string& values) {
        std::ofstream(path) << R"({"m": {"description": "d", "groups": [{"scenes": ["corner"], "kernels": ["ssdo"],
            "samples": [16], "blurs": [4], "params": {"ssdo_mode": )" << values << R"(}, "resolutions": ["full"],
            "sizes": ["160x90"], "apis": ["vk"], "stages": ["compute"]}]}})";
    };
    write(R"(["radiance", 0])");
    auto m = plan::loadMatrix(path, "m");
    ASSERT_TRUE(m) << m.error().message;
    std::set<double> modes;
    for (const auto& c : m->expand()) modes.insert(c.param("ssdo_mode"));
    EXPECT_EQ(modes, (std::set<double>{0, 1}));
    write(R"(["radiant"])");
    m = plan::loadMatrix(path, "m");
    ASSERT_FALSE(m);
    EXPECT_NE(m.error().message.find("params.ssdo_mode has \"radiant\": must be one of visibility, radiance"),
              std::string::npos)
        << m.error().message;
    fs::remove_all(dir);
}

// A group may leave samples out (each kernel at its default), and a
// parameter that one kernel of a mixed group reads stays out of the
// other's ids: alchemy runs once, gtao once a slice count.
TEST(ConfigId, MatrixGroupsWithoutSamplesAndMixedKernels) {
    const fs::path dir = fs::temp_directory_path() / "cavity_matrix_mixed";
    fs::create_directories(dir);
    const std::string path = (dir / "matrices.json").string();
    std::ofstream(path) << R"({"m": {"description": "d", "groups": [{"scenes": ["corner"], "kernels": ["alchemy", "gtao"],
        "blurs": [4], "params": {"slices": [1, 3]}, "resolutions": ["full"], "sizes": ["160x90"], "apis": ["vk"],
        "stages": ["compute"]}]}})";
    auto m = plan::loadMatrix(path, "m");
    ASSERT_TRUE(m) << m.error().message;
    std::vector<std::string> ids;
    for (const auto& c : m->expand()) ids.push_back(configId(c));
    EXPECT_EQ(ids, (std::vector<std::string>{"corner/alchemy/n16/b4/full/160x90/vk/compute",
                                             "corner/gtao/n16/b4/slices=1/full/160x90/vk/compute",
                                             "corner/gtao/n16/b4/slices=3/full/160x90/vk/compute"}));
    fs::remove_all(dir);
}

TEST(ConfigId, DistinctInEveryMatrix) {
    std::ifstream in(std::string(CAVITY_SOURCE_DIR) + "/baselines/matrices.json");
    const auto doc = nlohmann::json::parse(in);
    for (const auto& [name, _] : doc.items()) {
        auto m = plan::loadMatrix(std::string(CAVITY_SOURCE_DIR) + "/baselines/matrices.json", name);
        ASSERT_TRUE(m) << m.error().message;
        // The product before expand()'s de-duplication by id.
        std::vector<RunConfig> raw;
        for (const auto& g : m->groups) {
            auto ks = g.kernels;
            if (ks.size() == 1 && ks[0] == "all") ks = aoKernels();
            for (const auto& scene : g.scenes)
                for (const auto& k : ks)
                    for (int n : g.samples)
                        for (int b : g.blurs)
                            for (bool half : g.half)
                                for (auto [w, h] : g.sizes)
                                    for (auto api : g.apis)
                                        for (auto stage : g.stages) {
                                            if (half && !supportsHalf(k)) continue;
                                            RunConfig c = with({{"scene", scene.c_str()}}, k);
                                            c.params["samples"] = n;
                                            c.params["blur"] = b;
                                            c.half = half;
                                            c.width = w, c.height = h, c.api = api, c.stage = stage;
                                            // Every combination of the group's other parameters.
                                            std::vector<RunConfig> combos{c};
                                            for (const auto& [param, values] : g.params) {
                                                std::vector<RunConfig> next;
                                                for (const auto& base : combos)
                                                    for (double v : values) {
                                                        RunConfig one = base;
                                                        one.params[param] = v;
                                                        next.push_back(one);
                                                    }
                                                combos = std::move(next);
                                            }
                                            raw.insert(raw.end(), combos.begin(), combos.end());
                                        }
        }
        SCOPED_TRACE("matrix " + name);
        expectIdsMatchContent(raw);
        // The same matrix with every configuration at a second radius too.
        auto twice = raw;
        for (auto c : raw) {
            // No kernel's default, and no radius a group sets.
            c.params["radius"] = c.params.count("radius") ? c.params["radius"] * 1.37 : 0.37;
            twice.push_back(c);
        }
        expectIdsMatchContent(twice);
        std::set<std::string> ids;
        for (const auto& c : twice) ids.insert(configId(c));
        EXPECT_EQ(ids.size(), m->expand().size() * 2);
    }
}

TEST(ConfigId, DistinctInTheBenchmarkSweep) {
    for (const auto& axes : {gpuSweep(), cpuSweep()})
        expectIdsMatchContent(benchmarkSweep(axes, {gpu::Api::OpenGL, gpu::Api::Vulkan}));
}

TEST(RunSweep, EveryKernelParameterSweeps) {
    const fs::path dir = fs::temp_directory_path() / ("cavity-ids-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const auto [code, out] = test::runBinary(CAVITY_EXE, "run --backend vk --res 32x18 --frames 1 --warmup 0"
                                                         " --radius 0.5,1.0 --out " + dir.string());
    ASSERT_EQ(code, 0) << out;
    EXPECT_TRUE(fs::is_directory(dir / "corner/alchemy/n16/b4/full/32x18/vk/compute")) << out;
    EXPECT_TRUE(fs::is_directory(dir / "corner/alchemy/n16/b4/radius=1/full/32x18/vk/compute")) << out;
    std::ifstream in(dir / "results.json");
    const auto doc = nlohmann::json::parse(in);
    std::set<std::string> ids;
    for (const auto& r : doc["runs"]) ids.insert(r["id"].get<std::string>());
    EXPECT_EQ(ids.size(), 2u);
    fs::remove_all(dir);
}
