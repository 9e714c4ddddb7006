// Writing a render folder, what cavity_render leaves for `cavity gate judge`:
//   DIR/manifest.json                       render_manifest.h, written last
//   DIR/images/<id>/<image>.f32z            repetition 0 (image_file.h)
//   DIR/images/<id>/<image>.rep<K>.f32z     repetition K, only where its digest
//                                           differs from repetition 0's
// A later repetition that matches repetition 0 costs a digest in the
// manifest, not a file, so ten renders of a matrix come back from the GPU
// machine at the size of one unless something is not deterministic. And an
// image bit-identical to one already stored for the same baseline key (the
// other API or stage of the configuration: they share one baseline) names
// that file instead of writing its own.
#pragma once

#include "render/namespace.h"
#include "plan/approvals.h"
#include "render/render_manifest.h"
#include "render/rendering.h"

#include <map>
#include <string>

namespace cavity::render {

class FolderWriter {
public:
    // `manifest` carries the header (matrix, hash, commit, command, shard,
    // filter, repeat); the writer fills in devices and configurations.
    // `approved`: images whose digest is approved for the device's class are
    // recorded by digest alone, no file (the judge decides them by digest).
    // So are images that Rendering::judged says passed where they were
    // rendered; the record of each judged image goes into the manifest.
    FolderWriter(std::string dir, RenderManifest manifest, plan::Approvals approved = {});

    // Removes a manifest left by an earlier render into the same folder, so
    // that a render that dies half way leaves a folder the judge refuses.
    Status begin();
    Status add(Rendering&& r);
    Status finish(const std::vector<BackendFailure>& failures, double seconds);

    const RenderManifest& manifest() const { return manifest_; }
    uint64_t bytesWritten() const { return bytes_; }
    int filesWritten() const { return files_; }

private:
    std::string dir_;
    RenderManifest manifest_;
    plan::Approvals approved_;
    std::map<size_t, size_t> byIndex_;   // matrix index -> manifest_.configs position
    // (baseline key, image, digest) -> the file holding it and its size
    std::map<std::string, std::pair<std::string, uint64_t>> stored_;
    uint64_t bytes_ = 0;
    int files_ = 0;
};

}  // namespace cavity::render
