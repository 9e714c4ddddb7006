// Which depth-pyramid levels the gate reaches. The fast kernels read a
// sample's depth from a coarser level the farther it lands from its pixel
// (include/pyramid.glsl: level floor(log2 h) - 3, up to the last): at
// 1920x1080 they read every level, while in the small images of the CPU
// matrices hardly any sample lands 64 px away, so a defect in the deep
// levels (the pick undo at level 3 and up, say) would pass every CPU gate.
// These tests run each configuration's passes on the CPU references, which
// count every depth they read per level (reference::pyramid::levelReads),
// and fail when the `ci` matrix leaves a level of a fast kernel untested,
// at full or at half resolution.
#include "gpu_fixture.h"
#include "pipeline/config_id.h"
#include "pipeline/pipeline.h"
#include "plan/matrix.h"
#include "reference/pyramid.h"
#include "reference/reference.h"
#include "core/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

namespace cavity::test {
namespace {

bool readsPyramid(const PassSpec& p) {
    for (const auto& in : p.inputs)
        if (in.name.rfind("zmip", 0) == 0) return true;
    return false;
}

// The configuration's passes on the CPU references, each fed what earlier
// ones made, up to the last pass that reads the pyramid; the depths read
// per level on the way.
Result<std::vector<long long>> levelsRead(const RunConfig& c) {
    const auto passes = buildPasses(c);
    size_t last = 0;
    for (size_t i = 0; i < passes.size(); ++i)
        if (readsPyramid(passes[i])) last = i;
    std::map<std::string, HostImage> images;
    reference::pyramid::levelReads().clear();
    for (size_t i = 0; i <= last; ++i) {
        const auto& pass = passes[i];
        const auto* k = kernels::find(pass.kernel);
        if (!k) return internal("no kernel " + pass.kernel);
        const auto params = kernels::withDefaults(*k, c.params);
        std::vector<HostImage> constants;
        constants.reserve(pass.inputs.size());
        std::vector<const HostImage*> inputs;
        for (const auto& in : pass.inputs) {
            if (in.source == ImageSource::Constant) {
                const auto* decl = kernels::findConstant(in.name);
                const auto levels = decl->make(params);
                constants.emplace_back(levels[0].width, levels[0].height, gpu::channelCount(decl->format));
                constants.back().pixels = levels[0].pixels;
                inputs.push_back(&constants.back());
                continue;
            }
            const auto it = images.find(in.name);
            const bool self = std::find(pass.outputs.begin(), pass.outputs.end(), in.name) != pass.outputs.end();
            if (it == images.end() && self) {
                // The pyramid pass reads the levels it writes; its reference
                // builds them from the position alone.
                constants.emplace_back(pass.half ? (c.width + 1) / 2 : c.width, pass.half ? (c.height + 1) / 2 : c.height, 1);
                inputs.push_back(&constants.back());
                continue;
            }
            if (it == images.end()) return internal(pass.name + " reads " + in.name + " before it is made");
            inputs.push_back(&it->second);
        }
        std::map<std::string, std::vector<float>> arrays;
        if (k->derive) k->derive(params, arrays);
        const int w = pass.half ? (c.width + 1) / 2 : c.width, h = pass.half ? (c.height + 1) / 2 : c.height;
        const auto frame = frameUniforms(w, h, c.width, c.height);
        reference::Context ctx{*k, params, arrays, frame, inputs};
        CAVITY_ASSIGN(auto outputs, reference::run(ctx));
        for (size_t o = 0; o < outputs.size() && o < pass.outputs.size(); ++o) images[pass.outputs[o]] = std::move(outputs[o]);
    }
    return reference::pyramid::levelReads();
}

bool isFast(const std::string& kernel) {
    for (const auto& p : buildPasses([&] {
             RunConfig c;
             c.kernel = kernel;
             return c;
         }()))
        if (readsPyramid(p)) return true;
    return false;
}

std::string levelList(const std::set<int>& levels) {
    std::string s;
    for (int l : levels) s += (s.empty() ? "" : ", ") + std::to_string(l);
    return s.empty() ? "none" : s;
}

// Every level of the pyramid, for each fast kernel at full and at half
// resolution, is read by some configuration of the matrix.
void expectEveryLevelRead(const std::string& name) {
    auto matrix = plan::loadMatrix(std::string(CAVITY_SOURCE_DIR) + "/baselines/matrices.json", name);
    ASSERT_TRUE(matrix) << matrix.error().message;
    const int levels = reference::pyramid::levelCount();
    ASSERT_GE(levels, 4);
    std::map<std::pair<std::string, bool>, std::set<int>> reached;   // (kernel, half) -> levels read
    std::set<std::string> seen;                                      // baseline keys: API and stage change nothing here
    for (const auto& c : matrix->expand()) {
        if (!isFast(c.kernel) || !seen.insert(plan::baselineKey(c)).second) continue;
        auto reads = levelsRead(c);
        ASSERT_TRUE(reads) << configId(c) << ": " << reads.error().message;
        auto& r = reached[{c.kernel, c.half}];
        for (size_t l = 0; l < reads->size(); ++l)
            if ((*reads)[l] > 0) r.insert(int(l));
    }
    ASSERT_FALSE(reached.empty()) << "no fast kernel in the " << name << " matrix";
    for (const auto& k : kernels::all()) {
        if (k.role != kernels::Role::Ao || !isFast(k.name)) continue;
        for (bool half : {false, true}) {
            if (half && !supportsHalf(k.name)) continue;
            const auto& r = reached[{k.name, half}];
            for (int l = 0; l < levels; ++l)
                EXPECT_TRUE(r.count(l)) << k.name << (half ? " half" : " full") << ": the " << name << " matrix never reads pyramid level "
                                        << l << " (it reads " << levelList(r) << "); add a configuration whose samples "
                                        << "land " << (8 << l) << " px or more from their pixel";
        }
    }
}

TEST(PyramidCoverage, CiMatrixReadsEveryLevelOfEveryFastKernel) { expectEveryLevelRead("ci"); }

// gpu-cpu is the matrix a GPU render is judged against on a CPU; its
// 320x180 group with a wider radius reaches levels 3 and 4.
TEST(PyramidCoverage, GpuCpuMatrixReadsEveryLevelOfEveryFastKernel) { expectEveryLevelRead("gpu-cpu"); }

// The levels each fast kernel reads at 1920x1080 on corner, at the defaults:
// what the CPU matrix above must reach. Slow on a CPU (the G-buffer march
// of 2 megapixels), so run by hand:
//   build/tests/test_gpu --gtest_also_run_disabled_tests --gtest_filter='*1080*'
TEST(PyramidCoverage, DISABLED_LevelsReadAt1080p) {
    for (const auto& k : kernels::all()) {
        if (k.role != kernels::Role::Ao || !isFast(k.name)) continue;
        for (bool half : {false, true}) {
            if (half && !supportsHalf(k.name)) continue;
            RunConfig c;
            c.kernel = k.name;
            c.half = half;
            c.width = 1920;
            c.height = 1080;
            ASSERT_TRUE(setParam(c, "scene", "corner").ok());
            auto reads = levelsRead(c);
            ASSERT_TRUE(reads) << reads.error().message;
            std::printf("%s:", configId(c).c_str());
            for (size_t l = 0; l < reads->size(); ++l) std::printf(" L%zu=%lld", l, (*reads)[l]);
            std::printf("\n");
        }
    }
}

}  // namespace
}  // namespace cavity::test
