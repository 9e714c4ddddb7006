// baselines/approvals.json: images approved per device class, by digest.
// Each entry says that the image `image` of baseline key `key` with digest
// `digest` is right (positive) or known wrong (negative) on `device_class`,
// with the API, stage and driver it was seen on, and who approved it, when
// and why. The model is Skia Gold's positives and negatives: a GPU is
// deterministic (one driver on one device gives one digest), so an
// unchanged build passes by digest, exactly, with no metric computed; a
// known-bad digest fails at once; anything else is judged with the
// tolerances against the stored reference.
#pragma once

#include "plan/namespace.h"
#include "result.h"

#include <string>
#include <vector>

namespace cavity::plan {

struct Approval {
    std::string key, image, digest;
    bool positive = true;
    std::string deviceClass, api, stage, driver;
    std::string by, when, why;
};

struct Approvals {
    std::vector<Approval> entries;
    // Entries whose digest is an older FNV-1a 64 (core/digest.h): still
    // matched, by that digest of the image, until migrated.
    int legacy = 0;
    // The entry for this key, image and digest: a negative on any class
    // (known bad anywhere), else a positive on `deviceClass`; null if none.
    const Approval* find(const std::string& key, const std::string& image, const std::string& digest,
                         const std::string& deviceClass) const;
    // The approved positive of this key and image on `deviceClass` nearest
    // to an image rendered with `api` and `stage`: the same API and stage,
    // else the same API, else the same stage, else any; the latest approved
    // among equals. Null when the class has none: the image is then judged
    // against the default class's reference (baselines/images).
    const Approval* reference(const std::string& key, const std::string& image, const std::string& deviceClass,
                              const std::string& api, const std::string& stage) const;
};

// A device's class as approvals name it: its name up to any " (" or "/"
// (llvmpipe's and lavapipe's carry an LLVM version there, NVIDIA's GL
// renderer "/PCIe/SSE2"), lower case, every run of other characters one '-':
// "NVIDIA H200" and "NVIDIA H200/PCIe/SSE2" are "nvidia-h200", "llvmpipe
// (LLVM 15.0.6, 256 bits)" is "llvmpipe".
std::string deviceClass(const std::string& deviceName);

// A missing file is no approvals; anything else must parse.
Result<Approvals> loadApprovals(const std::string& path);
// Written whole to a temporary file and renamed into place.
Status saveApprovals(const std::string& path, const Approvals& a);

}  // namespace cavity::plan
