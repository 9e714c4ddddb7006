// Every pass of every configuration of every matrix in baselines/matrices.json:
// the GLSL assemble() makes for it, and the SPIR-V glslang makes of that for
// Vulkan and for OpenGL, against the list recorded in tests/data/assembled.txt;
// and each pass's cost per pixel (the benchmark's bytes/s and the roofline's
// floors) on both stages, against tests/data/costs.txt.
// A move of the kernels' declarations (into packages) or of their files must
// leave every byte the GPU runs as it was, so every approved digest holds;
// this says which kernel and stage moved if one did. A kernel edit that is
// meant to change what runs re-records the list:
//   CAVITY_RECORD_ASSEMBLED=1 build/tests/test_gpu --gtest_filter='Assembled.*'
#include "compiler.h"
#include "core/digest.h"
#include "kernel.h"
#include "pipeline/pipeline.h"
#include "plan/matrix.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace {

namespace k = cavity::kernels;
namespace gpu = cavity::gpu;

const std::string kRoot = CAVITY_SOURCE_DIR;
const std::string kRecord = kRoot + "/tests/data/assembled.txt";
const std::string kCostRecord = kRoot + "/tests/data/costs.txt";

std::string digestOf(const void* data, size_t size) {
    return cavity::core::digestText(cavity::core::fnv1a64(data, size));
}

// "kernel stage WxH name=value.. : fetches bytes slots dram" in full precision.
std::string costLine(const k::KernelDecl& decl, const k::ParamValues& given, const k::PassShape& shape) {
    if (!decl.cost) return decl.name + " no cost";
    const k::ParamValues values = k::withDefaults(decl, given);
    const k::Cost cost = decl.cost(values, shape);
    std::ostringstream line;
    line.precision(17);
    line << decl.name << (shape.compute ? " compute " : " fragment ") << shape.workgroup.x << 'x' << shape.workgroup.y;
    for (const auto& [name, v] : values)
        if (k::declares(decl, name)) line << ' ' << name << '=' << v;
    line << " : " << cost.fetchesPerPixel << ' ' << cost.bytesPerPixel << ' ' << cost.fetchSlotsPerPixel << ' '
         << cost.dramBytesPerPixel;
    return line.str();
}

// "kernel stage glsl-digest vk-spirv-digest gl-spirv-digest", one line per
// distinct source; `costs` gets "kernel stage WxH fetches bytes slots dram"
// for each distinct parameter set, in full precision.
std::set<std::string> current(std::set<std::string>* costs = nullptr) {
    std::set<std::string> lines;
    std::set<std::string> seen;
    const auto names = nlohmann::json::parse(std::ifstream(kRoot + "/baselines/matrices.json"));
    for (const auto& [name, body] : names.items()) {
        auto m = cavity::plan::loadMatrix(kRoot + "/baselines/matrices.json", name);
        EXPECT_TRUE(m.ok()) << name;
        if (!m) continue;
        for (const auto& c : m->expand()) {
            for (const auto& pass : cavity::pipeline::buildPasses(c)) {
                const k::KernelDecl* decl = k::find(pass.kernel);
                EXPECT_NE(decl, nullptr) << pass.kernel;
                if (!decl) continue;
                int mips = 1;
                for (const auto& o : decl->outputs) mips = std::max(mips, o.mipLevels);
                const bool interleaved = decl->interleaved && k::interleaveValue(c.params) > 1;
                const auto stage = mips > 1 || interleaved ? gpu::Stage::Compute : c.stage;
                if (costs) costs->insert(costLine(*decl, c.params, {stage == gpu::Stage::Compute, decl->workgroup}));
                auto src = k::assemble(*decl, stage, {}, &c.params);
                EXPECT_TRUE(src.ok()) << pass.kernel;
                if (!src) continue;
                const std::string glsl = digestOf(src->glsl.data(), src->glsl.size());
                if (!seen.insert(pass.kernel + glsl).second) continue;
                std::ostringstream line;
                line << pass.kernel << ' ' << (stage == gpu::Stage::Compute ? "compute" : "fragment") << ' ' << glsl;
                for (const auto api : {gpu::Api::Vulkan, gpu::Api::OpenGL}) {
                    auto spirv = k::compileToSpirv(*src, api);
                    EXPECT_TRUE(spirv.ok()) << pass.kernel;
                    line << ' ' << (spirv ? digestOf(spirv->data(), spirv->size() * 4) : std::string("none"));
                }
                lines.insert(line.str());
            }
        }
    }
    return lines;
}

// The lines of a recorded list, or every line of `now` written there when
// CAVITY_RECORD_ASSEMBLED is set (then null: the test skips).
std::optional<std::set<std::string>> recordedOrRecord(const std::string& path, const std::set<std::string>& now) {
    if (std::getenv("CAVITY_RECORD_ASSEMBLED")) {
        std::ofstream out(path);
        for (const auto& l : now) out << l << "\n";
        return std::nullopt;
    }
    std::ifstream in(path);
    EXPECT_TRUE(in) << path << ": missing; record it with CAVITY_RECORD_ASSEMBLED=1";
    std::set<std::string> recorded;
    for (std::string l; std::getline(in, l);)
        if (!l.empty()) recorded.insert(l);
    return recorded;
}

TEST(Assembled, EveryMatrixPassCostsWhatWasRecorded) {
    std::set<std::string> now;
    (void)current(&now);
    // Beyond the matrices: every kernel at its defaults and with each
    // parameter at its least and greatest value, on both stages and in
    // three workgroup shapes (the tiled passes' costs follow the shape).
    for (const auto& decl : k::all()) {
        std::vector<k::ParamValues> sets = {{}};
        for (const auto& p : decl.params) {
            if (p.decl->max - p.decl->min > 1e6) continue;
            sets.push_back({{p.name(), p.decl->min}});
            sets.push_back({{p.name(), p.decl->max}});
        }
        for (const auto& values : sets)
            for (const k::PassShape shape : {k::PassShape{true, decl.workgroup}, k::PassShape{false, decl.workgroup},
                                             k::PassShape{true, {8, 8}}, k::PassShape{true, {32, 4}}})
                now.insert(costLine(decl, values, shape));
    }
    ASSERT_GT(now.size(), 50u);
    const auto recorded = recordedOrRecord(kCostRecord, now);
    if (!recorded) GTEST_SKIP() << "recorded " << now.size() << " costs in " << kCostRecord;
    for (const auto& l : now)
        EXPECT_TRUE(recorded->count(l)) << "not recorded (a kernel's cost changed): " << l;
    for (const auto& l : *recorded)
        EXPECT_TRUE(now.count(l)) << "recorded, and no longer made: " << l;
}

TEST(Assembled, EveryMatrixPassRunsTheRecordedGlslAndSpirv) {
    const auto now = current();
    ASSERT_GT(now.size(), 50u);
    if (std::getenv("CAVITY_RECORD_ASSEMBLED")) {
        std::ofstream out(kRecord);
        for (const auto& l : now) out << l << "\n";
        GTEST_SKIP() << "recorded " << now.size() << " sources in " << kRecord;
    }
    std::ifstream in(kRecord);
    ASSERT_TRUE(in) << kRecord << ": missing; record it with CAVITY_RECORD_ASSEMBLED=1";
    std::set<std::string> recorded;
    for (std::string l; std::getline(in, l);)
        if (!l.empty()) recorded.insert(l);
    for (const auto& l : now)
        EXPECT_TRUE(recorded.count(l)) << "not recorded (a kernel's source or SPIR-V changed): " << l;
    for (const auto& l : recorded)
        EXPECT_TRUE(now.count(l)) << "recorded, and no longer made: " << l;
}

}  // namespace
