// Every pass of every configuration of every matrix in baselines/matrices.json:
// the GLSL assemble() makes for it, and the SPIR-V glslang makes of that for
// Vulkan and for OpenGL, against the list recorded in tests/data/assembled.txt.
// A move of the kernels' declarations (into packages) or of their files must
// leave every byte the GPU runs as it was, so every approved digest holds;
// this says which kernel and stage moved if one did. A kernel edit that is
// meant to change what runs re-records the list:
//   CAVITY_RECORD_ASSEMBLED=1 build/tests/test_assembled
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
#include <set>
#include <sstream>

namespace {

namespace k = cavity::kernels;
namespace gpu = cavity::gpu;

const std::string kRoot = CAVITY_SOURCE_DIR;
const std::string kRecord = kRoot + "/tests/data/assembled.txt";

std::string digestOf(const void* data, size_t size) {
    return cavity::core::digestText(cavity::core::fnv1a64(data, size));
}

// "kernel stage glsl-digest vk-spirv-digest gl-spirv-digest", one line per
// distinct source.
std::set<std::string> current() {
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
