// DIR/manifest.json of a render folder, schema "cavity.render/1"
// (harness/render/render.schema.json; README.md, "The two-step gate"): what was
// rendered, from which matrix declaration, by which build, on which devices,
// and per configuration and repetition the images' files and digests, the
// per-pass median times and the determinism check. Everything the judge needs
// besides the pixels.
#pragma once

#include "render/namespace.h"
#include "backend.h"
#include "render/image_file.h"
#include "render/rendering.h"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cavity::render {

constexpr const char* kRenderSchema = "cavity.render/1";

struct ImageEntry {
    std::string name;             // "ao", "ao_blur", "color"
    std::string file;             // relative to the folder; empty: the same pixels as repetition 0
    StoredImage stored;           // shape, digest, file size (0 without a file)
    std::optional<RemoteCheck> judged;
};

struct RenderEntry {              // one repetition
    int repetition = 0;
    std::string error;
    int errorCode = 0;
    bool deterministic = true;
    std::vector<PassTime> timings;
    std::vector<ImageEntry> images;
};

struct ConfigEntry {
    size_t index = 0;             // in the matrix's expansion
    std::string id, key, api, device;
    std::vector<RenderEntry> renders;   // by repetition, 0 first
};

struct BackendError {
    std::string api;
    int code = 0;
    std::string message;
};

struct RenderManifest {
    std::string matrix, matrixHash, gitCommit, createdUtc, command, filter;
    int shardIndex = 0, shardCount = 1, repeat = 1;
    double seconds = 0;
    std::map<std::string, gpu::DeviceInfo> devices;   // by API name ("gl", "vk"), the backends that started
    std::vector<BackendError> backendErrors;
    std::vector<ConfigEntry> configs;
    std::vector<ReplacedSource> replaced;              // --kernel-source: what was rendered instead of kernels/
    std::vector<measure::PackageUsed> packages;                // packages from disk whose kernels were rendered
};

nlohmann::json toJson(const RenderManifest& m);
// The replaced kernel sources as render manifests and gate.json write them:
// [{"name", "file", "digest"}].
nlohmann::json replacedJson(const std::vector<ReplacedSource>& replaced);
Result<std::vector<ReplacedSource>> parseReplaced(const nlohmann::json& j, const std::string& path);
// Checks the schema and the type of every field; messages start with "PATH: ".
Result<RenderManifest> parseManifest(const nlohmann::json& j, const std::string& path);

}  // namespace cavity::render
