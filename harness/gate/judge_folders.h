// `cavity gate judge RENDER_DIR... [--baselines DIR] --out DIR`: the judging
// half of the gate on render folders that cavity_render wrote
// (harness/render/render_folder.h), one per shard or machine. Every folder is checked
// whole first (the manifest's schema and fields, its matrix declaration
// against the current baselines/matrices.json, its build against this one,
// shards that do not overlap, and every image file's header, size, zlib
// stream and digest), so that a bad folder is refused (exit 2, one line
// naming the file) before anything is written. Then each repetition of each
// configuration goes through gate_judge.h as in `cavity gate`.
#pragma once

#include "gate/namespace.h"
#include "gate/gate.h"

#include <string>
#include <vector>

namespace cavity::gate {

struct JudgeOptions {
    std::string baselines = "baselines";
    std::string out = "out/gate";
    bool quiet = false;
    bool enforceCpuBudgets = false;   // GateOptions::enforceCpuBudgets
    cavity::store::StoreOptions store;        // GateOptions::store
    // --shards I[,J...]/N: the shards the folders are meant to hold. Empty:
    // all N of them, so that a lost shard is refused, not judged as a pass.
    std::string shards;
};

Result<GateRun> judgeFolders(const std::vector<std::string>& dirs, const JudgeOptions& o);

}  // namespace cavity::gate
