// The judging half of the gate, shared by `cavity gate` (Renderings straight
// from the GPU) and `cavity gate judge` (Renderings read back from render
// folders): each checked image against its baseline (metrics.h, with the
// tolerances of baselines/manifest.json), each pass's median time against
// baselines/budgets.json, and the determinism check. Both paths hand the same
// floats to the same function, so their verdicts and metrics are equal.
#pragma once

#include "gate/namespace.h"
#include "plan/approvals.h"
#include "gate/gate.h"
#include "render/rendering.h"
#include "store/store.h"

#include <map>
#include <memory>
#include <optional>
#include <mutex>

#include <string>
#include <vector>

namespace cavity::gate {

struct Judge {
    std::string baselines;   // folder with manifest.json, budgets.json, images/
    Manifest manifest;
    Budgets budgets;
    Approvals approvals;     // approvals.json
    std::string out;         // the gate's output folder
    bool enforceCpuBudgets = false;   // GateOptions::enforceCpuBudgets
    // Judging where the images were rendered (cavity_render --store): no
    // file written (no OpenImageIO there), and an image whose class has no
    // approved reference is left for the judge at home (route "unjudged";
    // its file travels).
    bool remote = false;
    // Where approved references of a device class are fetched from, for an
    // image judged by tolerance against its own class's reference.
    std::shared_ptr<cavity::store::ImageStore> store;
    // The references fetched so far, by digest (a configuration's two APIs
    // and stages usually share one).
    std::shared_ptr<std::map<std::string, HostImage>> fetched = std::make_shared<std::map<std::string, HostImage>>();
    std::shared_ptr<std::mutex> fetchLock = std::make_shared<std::mutex>();
    // The store's first failure to answer (unreachable, stalled, refused):
    // every later fetch fails with it at once, so a dead store costs one
    // time-out a run, not one a configuration.
    std::shared_ptr<std::optional<Error>> storeDown = std::make_shared<std::optional<Error>>();
    // The approved reference with this digest, from the store (once).
    Result<HostImage> reference(const std::string& digest) const;
};

// Reads the tolerances and budgets, checks every baseline `configs` will be
// compared with (present ones must be readable and of the configuration's
// shape; a missing one is judged, not refused) and that `out` can be
// written. Writes nothing.
// `store`: where references of device classes are fetched from (opened
// here, contacted only when an image needs one).
// `remote`: Judge::remote (the baseline files, read only at home, are not
// checked).
Result<Judge> prepareJudge(const std::string& baselines, const std::vector<RunConfig>& configs, const std::string& out,
                           const cavity::store::StoreOptions& store = {}, bool remote = false);

// Judges one Rendering, writing its new images, the baselines as PNG and the
// diff heat-maps under out/images/<id>/ (out/images/<id>/rep<K>/ for a later
// repetition with pixels of its own). An image a later repetition holds only
// as a digest equal to repetition 0's takes repetition 0's check, `first`.
Result<ConfigResult> judgeRendering(const render::Rendering& r, const Judge& j, const ConfigResult* first = nullptr);

}  // namespace cavity::gate
