// What the cavity commands that read a gate's output share (gate_command.cpp,
// approve_command.cpp); only the cavity binary links them.
#pragma once

#include "cli.h"
#include "gate/gate.h"

#include <filesystem>
#include <map>
#include <string>
#include <utility>

namespace cavity::cli {

// A gate output folder's gate.json; a missing one says to run the gate first.
Result<gate::GateRun> loadGateJson(const std::string& dir);

// A path gate.json recorded for an image, as the same file under `dir`'s
// own images/ (a folder moved or downloaded is read whole).
std::string inFolder(const std::string& dir, const std::string& recorded);

// gate merge: the images/ of each configuration's shard (`owner`: id ->
// shard folder) copied under --out, replacing a previous merge's, and the
// merged results' image paths moved there. The merged folder is then read
// as an unsharded gate's: baselines update and approve take their images
// from it, and the shards' folders may go.
Status gatherShardImages(const std::map<std::string, std::string>& owner, const std::string& out, gate::GateRun& merged);

// A gate's or judge's output, made under `staging` (stagingDir(out): the
// run wrote its images there) and moved into `out` at the end, so that a
// gate killed or failing midway leaves the earlier run's output whole. The
// earlier reports go first, then images/ is replaced by this run's (or
// removed, when it wrote none) and the reports are written, gate.json last:
// a kill in that short step leaves images and no verdict, never an older
// verdict over newer images.
Status writeGateOutput(gate::GateRun& run, const std::filesystem::path& staging, const std::string& out,
                       const std::string& reportUrl);

// The files a gate run rendered in place of kernels/ or a package's own
// (--kernel-source), each read back and checked against the digest the run
// recorded: target -> (file given, its text). Without `take`
// (--with-kernel-source) a run with replaced sources is refused: its images
// are not what the tree renders. baselines update and approve accept them.
using SourceCopies = std::map<std::filesystem::path, std::pair<std::string, std::string>>;
Result<SourceCopies> kernelSourceCopies(const gate::GateRun& run, const std::string& root, const std::string& from,
                                        bool take);
Status copyKernelSources(const SourceCopies& copies, const gate::GateRun& run);

// --baselines's help, as every command that reads the baselines words it.
inline const std::string kBaselinesHelp =
    "folder with matrices.json, manifest.json, budgets.json, images/ (default: baselines/ of the checkout found "
    "from the working directory up, else of the source tree this binary was built from)";

}  // namespace cavity::cli
