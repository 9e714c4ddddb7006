// The cavity_render command line (README.md, "The two-step gate"):
//   cavity_render --matrix NAME [--baselines DIR] [--backend gl|vk|all] [--shard I/N]
//                 [--device K] [--filter REGEX] [--repeat N] [--validation] --out DIR
//   cavity_render quality [the flags of cavity quality]
#pragma once

#include "imports.h"
#include "render/rendering.h"
#include "store/store.h"

#include <optional>

#include <string>
#include <vector>

namespace cavity::render {


struct RenderCommand {
    bool help = false;                    // --help given: print helpText, exit 0, nothing else read
    std::string helpText;
    std::string matrix, baselines, out, filter;   // baselines: empty until found (flags::defaultBaselines)
    bool list = false;                    // --list: print the selection's ids, render nothing
    int shardIndex = 0, shardCount = 1;
    RenderOptions render;
    std::vector<ReplacedSource> replaced;   // --kernel-source, recorded in the manifest
    // --store (and --store-cache): judge here, against the images approved
    // for the device's class, and write only the images that fail.
    std::optional<cavity::store::StoreOptions> store;
};

// Every error names the flag, the value and what is allowed (flags declared
// once, parsed by CLI11 through cli/flags.h).
Result<RenderCommand> parseRenderFlags(const std::vector<std::string>& argv);

// Validates, renders, writes DIR; returns the process exit code: 0 every
// configuration rendered, 2 bad input (nothing written), 3 a backend did
// not start, 4 a configuration failed on the GPU (3 and 4 still write the
// folder, with the errors in the manifest for the judge to report); with
// --store, 5 or 6 as the gate's store errors.
int renderCommand(const std::vector<std::string>& argv);

}  // namespace cavity::render
