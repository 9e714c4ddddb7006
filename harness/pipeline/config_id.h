// A configuration's canonical id, built here and nowhere else; it names the
// configuration in results.json, the benchmark name, the JUnit test name,
// the baseline path and the --filter syntax:
//
//     corner/alchemy/n16/b4/full/320x180/vk/compute
//     scene / AO kernel / samples / blur radius / full|half / size / API / stage
// A rasterised G-buffer appends "+raster" to the scene: corner+raster/...
// An imported G-buffer (--gbuffer import, harness/images/gbuffer_import.h) puts the
// capture's file stem (importStem) in place of the scene, with "+import":
//     capture+import/alchemy/n16/b4/full/320x180/vk/compute
// A parameter shows in the id when it differs from the default of a kernel
// of the configuration's pipeline, so the id reads the pass list
// (pipeline.h), which reads the configuration (config.h).
#pragma once

#include "pipeline/namespace.h"
#include "core/config.h"

#include <string>

namespace cavity::pipeline {

std::string configId(const RunConfig& c);

}  // namespace cavity::pipeline