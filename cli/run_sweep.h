// `cavity run`'s flags and the sweep they describe: the declaration (--help,
// the parse, README's flag table), the parse into a Sweep, and the Sweep's
// configurations through the one axis expander (plan/axes.h).
#pragma once

#include "cli.h"
#include "measure/runner.h"

#include <map>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

namespace cavity::cli {

const CommandSpec& runSpec();

// What `cavity run` was asked for: the sweep's axes and how to run it.
struct Sweep {
    std::vector<std::string> backends{"all"};
    std::vector<std::string> kernels{"alchemy"};
    std::vector<std::string> scenes{"corner"};
    // Every kernel parameter given (--samples, --blur, --radius, ...): one
    // axis each, its values in the order given.
    std::map<std::string, std::vector<double>> params;
    std::vector<std::string> resolutions{"full"};
    std::vector<std::pair<int, int>> sizes{{320, 180}};
    std::vector<gpu::Stage> stages{gpu::Stage::Compute};
    std::vector<std::string> gbuffers{"sdf"};
    std::string gbufferFile;          // --gbuffer-file
    bool sizeGiven = false, sceneGiven = false;
    RunConfig base;
    RunOptions options;
    gpu::BackendOptions backend;
    std::string out = "out";
    bool list = false, quiet = false, table = false;
    std::optional<std::regex> filter;   // --filter
    // --kernel-source NAME=FILE: kernels/NAME replaced in every configuration
    // (options.overrides holds the texts; this, what results.json records).
    std::vector<pipeline::ReplacedSource> replaced;
    std::string filterText;
    std::string helpText;               // --help: print this, run nothing
};

// The flags as a Sweep; with --help, only helpText is set.
Result<Sweep> parseSweep(const std::vector<std::string>& argv);
// The sweep's configurations, validated, API left unset.
Result<std::vector<RunConfig>> expandSweep(const Sweep& s);

}  // namespace cavity::cli
