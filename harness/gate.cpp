#include "gate.h"

#include "gate_judge.h"
#include "rendering.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace cavity::gate {

namespace fs = std::filesystem;

bool ConfigResult::imagesPassed() const {
    for (const auto& i : images)
        if (!i.passed()) return false;
    return true;
}

bool ConfigResult::timingPassed() const {
    for (const auto& t : timings)
        if (!t.passed()) return false;
    return true;
}

int GateRun::exitCode() const {
    bool bad = false, backend = !backendErrors.empty(), regression = false;
    for (const auto& r : results) {
        bad |= r.errorCode == 2;
        backend |= r.errorCode == 3;
        regression |= !r.passed();
    }
    return bad ? 2 : backend ? 3 : regression ? 1 : 0;
}

std::string ConfigResult::label() const {
    return repetition ? id + " (repetition " + std::to_string(repetition) + ")" : id;
}

Result<GateRun> runGate(const GateOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    CAVITY_ASSIGN(Matrix matrix, loadMatrix((fs::path(o.baselines) / "matrices.json").string(), o.matrix));
    CAVITY_ASSIGN(auto entries, selectEntries(matrix, o.shardIndex, o.shardCount, o.filter));
    std::vector<RunConfig> configs;
    for (const auto& e : entries) configs.push_back(e.config);
    CAVITY_ASSIGN(const Judge judge, prepareJudge(o.baselines, configs, o.out));

    GateRun run;
    run.matrix = o.matrix;
    run.shardIndex = o.shardIndex;
    run.shardCount = o.shardCount;
    render::RenderOptions ro;
    ro.device = o.device;
    ro.validation = o.validation;
    ro.overrides = o.overrides;
    auto sink = [&](render::Rendering&& rendering) -> Status {
        CAVITY_ASSIGN(ConfigResult r, judgeRendering(rendering, judge));
        if (r.error.empty()) std::fprintf(stderr, "gate: %-56s %s\n", r.id.c_str(), r.passed() ? "pass" : "FAIL");
        run.results.push_back(std::move(r));
        return {};
    };
    std::vector<render::BackendFailure> failures;
    CAVITY_TRY(render::renderEntries(matrix, entries, ro, sink, &failures));
    for (const auto& f : failures) run.backendErrors.push_back(f.message);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

}  // namespace cavity::gate
